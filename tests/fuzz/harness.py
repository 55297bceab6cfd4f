"""Run one mutant through one robotdesc command and judge the outcome.

A case lives in its own folder: `case/robot.urdf` (the mutant), `pkgs/fuzzpkg` (a package
holding the broken mesh, if any) and `out/` (the only place a command may write). The command
runs in-process (`robotdesc.cli.main` with captured output, a SIGALRM timeout) or, for a
sample, as a subprocess. The verdict: the exit code is 0, 1 or 2; no traceback or internal-error
text is printed; it finished in time; nothing was written outside `out/`.
"""

from __future__ import annotations

import contextlib
import io
import os
import random
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from fuzz.mutate import Mutant

ALLOWED_EXITS = frozenset({0, 1, 2})
_BAD_TEXT = ("Traceback (most recent call last)", "internal error", "This is a bug")
FUZZ_PACKAGE = "fuzzpkg"

#: Commands and their extra arguments; {out} is the case's output folder.
COMMANDS: dict[str, list[str]] = {
    "lint": ["--format", "json", "-o", "{out}/report.json"],
    "lint-text": [],
    "lint-sarif": ["--format", "sarif", "-o", "{out}/report.sarif"],
    "expand": ["-o", "{out}/robot.urdf"],
    "inertia": [],
    "info": [],
    "srdf": ["--samples", "20", "-o", "{out}/robot.srdf", "--jobs", "1"],
    "view": ["-o", "{out}/view.html", "--max-faces", "500", "--no-lint"],
    "report": ["-o", "{out}/report.html", "--no-view", "--jobs", "1"],
    "collision": ["--method", "primitive", "--out", "{out}/collision", "--jobs", "1"],
}
#: How often each command is drawn (the cheap ones more often).
WEIGHTS = {"lint": 30, "lint-text": 10, "lint-sarif": 5, "expand": 20, "inertia": 10,
           "info": 8, "srdf": 4, "view": 6, "report": 3, "collision": 4}


class Hang(BaseException):
    """The command did not finish in time (BaseException: the CLI must not swallow it)."""


@dataclass(frozen=True)
class Outcome:
    """What one run did.

    Attributes:
        command: the command name (a key of COMMANDS).
        exit_code: its exit code (None when it hung).
        output: stdout and stderr, truncated to 4 kB for the record.
        output_bytes: how many bytes it printed.
        seconds: wall-clock time.
        written_outside: files created or changed outside the output folder.
        problems: why the verdict is a failure (empty: it passed).
    """

    command: str
    exit_code: int | None
    output: str
    output_bytes: int
    seconds: float
    written_outside: tuple[str, ...] = ()
    problems: tuple[str, ...] = field(default=())

    @property
    def ok(self) -> bool:
        return not self.problems


def prepare_case(root: Path, mutant: Mutant, name: str = "robot.urdf") -> Path:
    """Write the mutant (and its broken mesh package) under `root`; returns the description."""
    case = root / "case"
    (root / "out").mkdir(parents=True, exist_ok=True)
    case.mkdir(parents=True, exist_ok=True)
    package = root / "pkgs" / FUZZ_PACKAGE
    (package / "meshes").mkdir(parents=True, exist_ok=True)
    (package / "package.xml").write_text(
        f"<package format=\"3\"><name>{FUZZ_PACKAGE}</name><version>0.0.0</version>"
        "<description>fuzz</description><maintainer email=\"a@b.c\">a</maintainer>"
        "<license>BSD</license></package>\n")
    if mutant.mesh:
        (package / "meshes" / mutant.mesh[0]).write_bytes(mutant.mesh[1])
    target = case / name
    target.write_bytes(mutant.data)
    return target


def command_line(command: str, target: Path, root: Path, package_paths: list[str]) -> list[str]:
    """The argv (without the program name) of one run."""
    verb = command.split("-")[0]
    paths = [arg for path in [str(root / "pkgs"), *package_paths]
             for arg in ("--package-path", path)]
    extra = [arg.format(out=root / "out") for arg in COMMANDS[command]]
    return [verb, str(target), *paths, *extra]


def _snapshot(root: Path) -> dict[str, tuple[int, int]]:
    found = {}
    for dirpath, _, files in os.walk(root):
        if os.path.abspath(dirpath).startswith(str(root / "out")):
            continue
        for name in files:
            path = os.path.join(dirpath, name)
            with contextlib.suppress(OSError):
                stat = os.stat(path)
                found[path] = (stat.st_size, stat.st_mtime_ns)
    return found


def _on_alarm(signum: int, frame: object) -> None:
    raise Hang()


def run_in_process(argv: list[str], timeout_s: float) -> tuple[int | None, str, int]:
    """Run `robotdesc.cli.main(argv)` with captured stdout/stderr and a SIGALRM timeout."""
    from robotdesc.cli import main

    out_bytes, err_bytes = io.BytesIO(), io.BytesIO()
    out = io.TextIOWrapper(out_bytes, encoding="utf-8", errors="replace", write_through=True)
    err = io.TextIOWrapper(err_bytes, encoding="utf-8", errors="replace", write_through=True)
    previous = signal.signal(signal.SIGALRM, _on_alarm)
    signal.setitimer(signal.ITIMER_REAL, timeout_s)
    code: int | None
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(argv)
    except Hang:
        code = None
    except SystemExit as exc:  # a command must return, but judge what it meant
        code = exc.code if isinstance(exc.code, int) else 2
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    text = out_bytes.getvalue() + err_bytes.getvalue()
    return code, text[:4096].decode("utf-8", "replace") + _tail(text), len(text)


def run_subprocess(argv: list[str], timeout_s: float, cwd: Path) -> tuple[int | None, str, int]:
    """Run `python -m robotdesc ARGV` as a separate process."""
    try:
        done = subprocess.run([sys.executable, "-m", "robotdesc", *argv], cwd=cwd,
                              capture_output=True, timeout=timeout_s)
    except subprocess.TimeoutExpired:
        return None, "", 0
    text = done.stdout + done.stderr
    return done.returncode, text[:4096].decode("utf-8", "replace") + _tail(text), len(text)


def _tail(text: bytes) -> str:
    """The last lines too, where a traceback would end, when the output was cut."""
    return "\n...\n" + text[-2048:].decode("utf-8", "replace") if len(text) > 4096 else ""


def run_case(root: Path, command: str, target: Path, package_paths: list[str], *,
             timeout_s: float = 120.0, subprocess_run: bool = False) -> Outcome:
    """Run one command on one prepared case and judge it."""
    argv = command_line(command, target, root, package_paths)
    before = _snapshot(root)
    started = time.monotonic()
    cwd = os.getcwd()
    os.chdir(root / "case")
    try:
        if subprocess_run:
            code, text, size = run_subprocess(argv, timeout_s, root / "case")
        else:
            code, text, size = run_in_process(argv, timeout_s)
    finally:
        os.chdir(cwd)
    seconds = time.monotonic() - started
    after = _snapshot(root)
    written = tuple(sorted(p for p, stamp in after.items() if before.get(p) != stamp))
    problems = []
    if code is None:
        problems.append(f"hang (> {timeout_s:.0f} s)")
    elif code not in ALLOWED_EXITS:
        problems.append(f"exit {code}")
    problems += [f"printed {bad!r}" for bad in _BAD_TEXT if bad in text]
    if written:
        problems.append(f"wrote outside the output folder: {', '.join(written[:3])}")
    limit = 64 * 1024 * 1024
    if size > limit:
        problems.append(f"printed {size} bytes")
    return Outcome(command, code, text, size, seconds, written, tuple(problems))


def pick_command(rng: random.Random, allowed: list[str] | None = None) -> str:
    names = [name for name in WEIGHTS if allowed is None or name in allowed]
    return rng.choices(names, weights=[WEIGHTS[n] for n in names])[0]
