"""Starting the xacro worker process, and a worker started before its job is known.

The worker (`robotdesc.expansion.worker`) imports what it needs, then waits for its job on
stdin; it limits and confines itself once the job names its roots, before any xacro runs.
`start_early` starts it as soon as a command knows it will expand (a cold `robotdesc lint`),
so that its interpreter start and imports run beside the parent's own work; this module
imports nothing of robotdesc, and `subprocess` only when it starts or ends a worker, so that
importing it costs a command that starts none (a lint the result cache answers) nothing.
"""

from __future__ import annotations

import atexit
import logging
import os
import signal
import sys
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import subprocess

log = logging.getLogger(__name__)

#: The worker started ahead of its job (`start_early`), with the id of the process that
#: started it (a forked child never takes its parent's worker).
_EARLY: list[tuple[int, subprocess.Popen[bytes]]] = []
_EARLY_CLEANUP: list[bool] = []
#: [the process that said so, how many more expansions follow the next one] (`expect_more`).
_MORE: list[int] = []


def _worker_pythonpath() -> str:
    """Where the worker finds robotdesc and installed packages (never the current folder)."""
    own = str(Path(__file__).resolve().parents[2])
    site = [p for p in sys.path if p and ("site-packages" in p or "dist-packages" in p)]
    return os.pathsep.join(dict.fromkeys([own, *site]))


def _worker_environment() -> dict[str, str]:
    env = {"PYTHONPATH": _worker_pythonpath(), "PATH": os.defpath, "LC_ALL": "C.UTF-8",
           "PYTHONDONTWRITEBYTECODE": "1", "PYTHONIOENCODING": "utf-8"}
    return env


def launch() -> subprocess.Popen[bytes]:
    """Start a worker process: it imports what it needs, then waits for its job on stdin
    (it reads nothing else, and confines itself once the job names its roots).

    Raises:
        OSError: the interpreter could not be started.
    """
    # -S: no site module (its .pth hooks cost 5-30 ms and run code the worker does not need);
    # the worker gets the parent's import path instead, without the current folder.
    search_path = [entry for entry in sys.path if entry]
    bootstrap = (f"import sys; sys.path[:] = {search_path!r}; "
                 f"from robotdesc.expansion.worker import main; main({os.getpid()})")
    command = [sys.executable, "-B", "-S", *(["-P"] if sys.version_info >= (3, 11) else []),
               "-c", bootstrap]
    import subprocess  # only when a worker starts

    return subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, env=_worker_environment(),
                            start_new_session=True)


def start_early() -> None:
    """Start the worker process now, before its job is known, for the next `runner.run_worker`
    of this process: the worker's interpreter start and imports (about 50 ms) then run beside
    this process's own work up to the expansion (a cold `robotdesc lint`).

    The worker is the same process `run_worker` would start (same command, environment and
    limits; it reads its job, then limits and confines itself, before any xacro runs). One
    that no expansion takes (an expansion-cache hit, a plain URDF, an error first) is killed
    when this process exits; a failure to start it is left to `run_worker` to report.
    """
    if any(owner == os.getpid() for owner, _ in _EARLY):
        return
    try:
        proc = launch()
    except OSError as exc:
        log.debug("the xacro worker was not started early: %s", exc)
        return
    _EARLY.append((os.getpid(), proc))
    if not _EARLY_CLEANUP:
        _EARLY_CLEANUP.append(True)
        atexit.register(drop_early)


def expect_more(count: int) -> None:
    """Say that `count` more expansions follow the next one in this process (a lint of
    several xacro targets one after the other): each expansion that ends then starts the
    next one's worker (`start_next`), whose start-up runs beside the lint of the previous."""
    _MORE[:] = [os.getpid(), count]


def more_expected() -> bool:
    """Whether `expect_more` said that more expansions follow the current one here."""
    return bool(_MORE) and _MORE[0] == os.getpid() and _MORE[1] > 0


def start_next() -> None:
    """After an expansion: start the next one's worker now when `expect_more` said one
    follows (the worker of a target whose result turns out cached is killed at the end)."""
    if more_expected():
        _MORE[1] -= 1
        start_early()


def take_early() -> subprocess.Popen[bytes] | None:
    """The worker `start_early` started in this process, if it is still waiting for a job."""
    mine = [entry for entry in _EARLY if entry[0] == os.getpid()]
    _EARLY[:] = [entry for entry in _EARLY if entry[0] != os.getpid()]
    for _, proc in mine:
        if proc.poll() is None:
            return proc
        kill_group(proc)  # ended before it was given a job: reap it, start another
    return None


def drop_early() -> None:
    """Kill the worker `start_early` started in this process if no expansion took it."""
    for owner, proc in list(_EARLY):
        if owner == os.getpid():
            _EARLY.remove((owner, proc))
            kill_group(proc)


def kill_group(proc: subprocess.Popen[bytes]) -> None:
    """Kill the worker's whole process group (it leads its own session) and reap it."""
    import subprocess  # imported already: `proc` is one of its processes

    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        log.warning("the xacro worker (pid %d) did not end after SIGKILL", proc.pid)
