"""The pre-commit hook (.pre-commit-hooks.yaml) runs on a sample description repository.

pre-commit installs the hook from a local clone of robotdesc (a temporary git repository
holding this working tree's sources). No network: pip builds robotdesc into the hook's
virtualenv without build isolation, an index or its dependencies (`install-hooks`); the hook
then runs with PYTHONPATH naming the site-packages of the interpreter running the tests (a
venv's or the system's: where robotdesc's dependencies were installed), so the test never
depends on the base interpreter. About 12 s (building the hook's virtualenv).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest
import yaml

REPO = Path(__file__).resolve().parents[1]
GOOD = """<?xml version="1.0"?>
<robot name="r">
  <link name="a"/>
  <link name="b"/>
  <joint name="j" type="continuous">
    <parent link="a"/>
    <child link="b"/>
    <axis xyz="0 0 {z}"/>
  </joint>
</robot>
"""


def git(cwd: Path, *args: str) -> str:
    return subprocess.run(["git", "-c", "user.name=t", "-c", "user.email=t@t.invalid",
                           "-c", "commit.gpgsign=false", *args], cwd=cwd, check=True,
                          capture_output=True, text=True).stdout.strip()


def test_hook_manifest_is_valid() -> None:
    (hook,) = yaml.safe_load((REPO / ".pre-commit-hooks.yaml").read_text())
    assert hook["id"] == "robotdesc" and hook["entry"] == "robotdesc lint"
    assert hook["language"] == "python" and hook["pass_filenames"] is False
    import re

    pattern = re.compile(hook["files"])
    for name in ("urdf/robot.urdf.xacro", "meshes/a.STL", "robotdesc.toml", "x.urdf"):
        assert pattern.search(name), name
    assert not pattern.search("README.md")


@pytest.mark.skipif(shutil.which("git") is None, reason="needs git")
def test_precommit_runs_the_hook_on_a_sample_repository(tmp_path) -> None:
    pytest.importorskip("pre_commit")
    hook_repo = tmp_path / "robotdesc"
    shutil.copytree(REPO / "src", hook_repo / "src",
                    ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    for name in ("pyproject.toml", "README.md", ".pre-commit-hooks.yaml"):
        shutil.copy(REPO / name, hook_repo / name)
    git(hook_repo, "init", "-q")
    git(hook_repo, "add", ".")
    git(hook_repo, "commit", "-qm", "robotdesc")
    rev = git(hook_repo, "rev-parse", "HEAD")

    sample = tmp_path / "sample_description"
    (sample / "urdf").mkdir(parents=True)
    (sample / "urdf" / "robot.urdf").write_text(GOOD.format(z=2))
    (sample / "robotdesc.toml").write_text('select = ["J"]\n')
    (sample / ".pre-commit-config.yaml").write_text(yaml.safe_dump({"repos": [{
        "repo": str(hook_repo), "rev": rev, "hooks": [{"id": "robotdesc"}]}]}))
    git(sample, "init", "-q")
    git(sample, "add", ".")

    install_env = dict(os.environ, PRE_COMMIT_HOME=str(tmp_path / "pre-commit-home"),
                       PIP_NO_INDEX="1", PIP_NO_DEPS="1", PIP_NO_BUILD_ISOLATION="0",
                       PIP_DISABLE_PIP_VERSION_CHECK="1")
    install_env.pop("PYTHONPATH", None)
    installed = subprocess.run([sys.executable, "-m", "pre_commit", "install-hooks"], cwd=sample,
                               env=install_env, capture_output=True, text=True, check=False)
    assert installed.returncode == 0, installed.stdout + installed.stderr
    # The running interpreter's own site-packages (in a venv, not the base interpreter's):
    # the hook finds robotdesc's dependencies there.
    site = dict.fromkeys(sysconfig.get_paths()[key] for key in ("purelib", "platlib"))
    env = dict(install_env, PYTHONPATH=os.pathsep.join(site))
    command = [sys.executable, "-m", "pre_commit", "run", "--all-files", "--color", "never"]
    failing = subprocess.run(command, cwd=sample, env=env, capture_output=True, text=True,
                             check=False)
    assert failing.returncode == 1, failing.stdout + failing.stderr
    assert "robotdesc lint" in failing.stdout and "Failed" in failing.stdout
    assert "J107 [warning] joint 'j' axis has length 2" in failing.stdout

    (sample / "urdf" / "robot.urdf").write_text(GOOD.format(z=1))
    git(sample, "add", ".")
    passing = subprocess.run(command, cwd=sample, env=env, capture_output=True, text=True,
                             check=False)
    assert passing.returncode == 0, passing.stdout + passing.stderr
    assert "Passed" in passing.stdout
