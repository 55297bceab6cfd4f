"""No doc tells a user to install a release that does not exist: robotdesc is not on the
package index and has no release tags. Every `pip install` the docs write installs from a
clone (`.`, `.[extra]`), a built wheel, or `git+<repository URL>@<commit>`; a pre-commit
`rev:` is a commit. The slow test runs the local forms in a fresh virtual environment."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
import tarfile
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
DOCS = sorted([REPO / "README.md", REPO / ".pre-commit-hooks.yaml", REPO / "docs" / "tutorial.py",
               *(REPO / "docs").glob("*.md"), *(REPO / "robots").glob("*/README.md"),
               REPO / "benchmarks" / "README.md"])
#: A `pip install ...` command up to the end of its shell command or comment.
_PIP = re.compile(r"pip install ([^\n`#|;&]*)")
_COMMIT = re.compile(r"<commit>|[0-9a-f]{40}")
_OWN = re.compile(r"^robotdesc(\[[^\]]*\])?([<>=!~].*)?$", re.IGNORECASE)


def install_commands() -> list[tuple[str, list[str]]]:
    """(file name, the arguments of one `pip install`) for every one the docs write."""
    found = []
    for doc in DOCS:
        for match in _PIP.finditer(doc.read_text(encoding="utf-8")):
            try:
                words = shlex.split(match.group(1))
            except ValueError:  # an unbalanced quote in prose
                words = match.group(1).split()
            found.append((doc.relative_to(REPO).as_posix(), words))
    return found


def install_kind(word: str) -> str:
    """What a `pip install` argument installs: "clone", "wheel", "git", "robotdesc-index"
    (the dishonest form) or "other" (another project's package)."""
    if re.fullmatch(r"\.(\[[\w,\-]+\])?", word):
        return "clone"
    if word.endswith(".whl"):
        return "wheel"
    if word.startswith("git+"):
        return "git" if "@" in word.split("//", 1)[-1] and _COMMIT.search(
            word.rsplit("@", 1)[-1]) else "git-without-commit"
    return "robotdesc-index" if _OWN.match(word) else "other"


def test_every_install_command_is_an_honest_form() -> None:
    commands = install_commands()
    assert len(commands) >= 10
    kinds = set()
    for name, words in commands:
        for word in words:
            if word.startswith("-"):
                continue
            kind = install_kind(word)
            assert kind not in ("robotdesc-index", "git-without-commit"), (name, words)
            kinds.add(kind)
    assert {"clone", "wheel", "git"} <= kinds


def test_the_user_guide_names_every_form() -> None:
    guide = (REPO / "docs" / "user-guide.md").read_text(encoding="utf-8")
    kinds = {install_kind(word) for name, words in install_commands()
             if name == "docs/user-guide.md" for word in words}
    assert {"clone", "wheel", "git"} <= kinds
    assert "not on the package index" in guide


def test_precommit_rev_is_a_commit() -> None:
    revs = [(doc.name, rev) for doc in DOCS
            for rev in re.findall(r"^[#\s]*rev:\s*(\S+)", doc.read_text(encoding="utf-8"),
                                  re.MULTILINE)]  # a YAML key, not prose
    assert revs
    for name, rev in revs:
        assert _COMMIT.fullmatch(rev), (name, rev)


def test_the_classifier() -> None:
    assert install_kind(".[kinematics]") == "clone" and install_kind(".") == "clone"
    assert install_kind("robotdesc") == install_kind("robotdesc[sim]>=0.1") == "robotdesc-index"
    assert install_kind("git+https://github.com/robotdesc/robotdesc@<commit>") == "git"
    assert install_kind("git+https://github.com/robotdesc/robotdesc") == "git-without-commit"
    assert install_kind("manifold3d") == "other"


def _source_copy(destination: Path) -> Path:
    """The repository's tracked files (as in a fresh clone), so that a build writes nothing
    into the working tree."""
    listed = subprocess.run(["git", "ls-files", "-z"], cwd=REPO, capture_output=True,
                            check=True).stdout.decode().split("\0")
    archive = destination / "source.tar"
    with tarfile.open(archive, "w") as tar:
        for name in filter(None, listed):
            if (REPO / name).exists():
                tar.add(REPO / name, arcname=name)
    clone = destination / "clone"
    with tarfile.open(archive) as tar:
        tar.extractall(clone, filter="data")
    return clone


@pytest.mark.slow
def test_the_local_forms_install_in_a_fresh_venv(tmp_path: Path) -> None:
    """`pip install .` from a clone, then the wheel built from it, in a new venv (its
    dependencies come from the package index configured for pip on this machine)."""
    clone = _source_copy(tmp_path)
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    python = str(venv / "bin" / "python")
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>\n')

    def works() -> None:
        version = subprocess.run([python, "-m", "robotdesc", "--version"], capture_output=True,
                                 text=True, cwd=tmp_path)
        assert version.returncode == 0 and version.stdout.startswith("robotdesc ")
        lint = subprocess.run([python, "-m", "robotdesc", "lint", str(robot)],
                              capture_output=True, text=True, cwd=tmp_path)
        assert lint.returncode in (0, 1) and "Traceback" not in lint.stderr, lint.stderr

    pip = [python, "-m", "pip", "install", "--quiet"]
    subprocess.run([*pip, "."], cwd=clone, check=True)  # the README's form
    works()
    subprocess.run([python, "-m", "pip", "wheel", "--quiet", "--no-deps", "-w", "dist", "."],
                   cwd=clone, check=True)
    (wheel,) = (clone / "dist").glob("robotdesc-*.whl")
    subprocess.run([python, "-m", "pip", "uninstall", "--quiet", "--yes", "robotdesc"],
                   check=True)
    subprocess.run([*pip, str(wheel)], check=True)
    works()
