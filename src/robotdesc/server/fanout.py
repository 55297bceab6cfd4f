"""The lints one save asks for, at once: a save in a macro file changes every variant that
includes it (the Engineer's three), and each variant's lint (parse, rules) is independent of
the others'. On Linux with more than one CPU, each but the last runs in a forked child of the
server, which shares the parsed session, the imports and the in-memory caches copy-on-write
and sends back its result without the model and the expansion (the parent has them); the
last runs here meanwhile. A child that fails in any way (an exception, a result it cannot
send, no answer within `CHILD_TIMEOUT_S`) is ended and its lint run again here, so that an
error surfaces exactly as a serial run raises it. Elsewhere every lint runs here, in turn.

The children never read stdin or write stdout (the LSP channel) and leave with `os._exit`,
flushing none of the parent's buffers.
"""

from __future__ import annotations

import dataclasses
import gc
import logging
import os
import pickle
import select
import signal
import sys
import time
from collections.abc import Callable, Sequence
from typing import TypeVar

from robotdesc.linting.result import LintResult

log = logging.getLogger(__name__)

#: A child that has not answered by then is ended (its lint is run again in the server), s.
CHILD_TIMEOUT_S = 60.0

Outcome = TypeVar("Outcome")


def can_fan_out() -> bool:
    """Whether lints may run in forked children here (Linux, more than one CPU)."""
    return sys.platform.startswith("linux") and hasattr(os, "fork") \
        and len(os.sched_getaffinity(0)) > 1


def run_all(jobs: Sequence[Callable[[], Outcome]]) -> list[Outcome]:
    """Every job's outcome, in order: all but the last in forked children when
    `can_fan_out()`, else each here in turn. A job's `LintResult` comes back without its
    model and expansion (`robot`, `expanded`: None); other outcomes as they are."""
    if len(jobs) < 2 or not can_fan_out():
        return [job() for job in jobs]
    children = [_fork(job) for job in jobs[:-1]]
    last = jobs[-1]()
    outcomes = [_collect(child, job) for child, job in zip(children, jobs[:-1])]
    return [*outcomes, last]


def _fork(job: Callable[[], object]) -> tuple[int, int] | None:
    """Start `job` in a child: (its pid, the pipe's read end), or None when it cannot fork."""
    try:
        read, write = os.pipe()
    except OSError:
        return None
    try:
        pid = os.fork()
    except OSError:
        os.close(read)
        os.close(write)
        return None
    if pid:
        os.close(write)
        return pid, read
    os.close(read)  # the child: lint, send, leave without running the parent's exit code
    gc.disable()  # short-lived: a collection would touch (copy) every page of the parent's heap
    code = 0
    try:
        _send(write, job())
    except BaseException:  # noqa: BLE001 (any failure: the parent runs the job itself)
        code = 1
    os._exit(code)


def _send(handle: int, outcome: object) -> None:
    """Pickle `outcome` (a `LintResult` without model and expansion) into the pipe."""
    if isinstance(outcome, LintResult):
        outcome = dataclasses.replace(outcome, robot=None, expanded=None)
    data = memoryview(pickle.dumps(outcome, protocol=pickle.HIGHEST_PROTOCOL))
    while data:
        data = data[os.write(handle, data):]


def _collect(child: tuple[int, int] | None, job: Callable[[], Outcome]) -> Outcome:
    """The child's outcome, or the job's own when the child failed."""
    if child is None:
        return job()
    pid, read = child
    chunks: list[bytes] = []
    deadline = time.monotonic() + CHILD_TIMEOUT_S
    try:
        while True:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([read], [], [], left)[0]:
                log.warning("a lint in a child process did not answer in %.0f s; linting "
                            "here", CHILD_TIMEOUT_S)
                os.kill(pid, signal.SIGKILL)
                chunks = []
                break
            chunk = os.read(read, 1 << 20)
            if not chunk:
                break
            chunks.append(chunk)
    finally:
        os.close(read)
        _, status = os.waitpid(pid, 0)
    if not chunks or not os.WIFEXITED(status) or os.WEXITSTATUS(status) != 0:
        return job()
    outcome: Outcome = pickle.loads(b"".join(chunks))  # from our own fork: trusted
    return outcome
