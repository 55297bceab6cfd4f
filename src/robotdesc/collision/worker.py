"""Run tasks in worker processes, one process per task, at most `jobs` at a time.

Native backends (fast-simplification, CoACD) can abort or segfault on bad input and can
stall: each task therefore runs in its own process (forked from a forkserver that has the
heavy modules imported, so a start costs milliseconds), with a wall-clock timeout. A crash,
a timeout or an exception is returned as a `TaskFailure` for that task; the other tasks
still complete. No shared pool a crash could break.
"""

from __future__ import annotations

import logging
import multiprocessing
import os
import signal
import sys
import time
import traceback
from contextlib import contextmanager
from dataclasses import dataclass
from multiprocessing.connection import wait
from typing import TYPE_CHECKING, Any, Callable, Iterator, Sequence

if TYPE_CHECKING:
    from multiprocessing.connection import Connection
    from multiprocessing.context import ForkServerContext, SpawnContext
    from multiprocessing.process import BaseProcess

    #: What a task's process sends back: ("ok", result, "") or ("exception", message,
    #: traceback).
    _Message = tuple[str, Any, str]
    _Pipe = Connection[_Message, _Message]

log = logging.getLogger(__name__)

#: Modules imported once in the forkserver, so that every worker starts warm.
PRELOAD = ["numpy", "scipy.spatial", "trimesh", "meshoptimizer", "fast_simplification",
           "robotdesc.collision.link"]


@dataclass(frozen=True)
class TaskFailure:
    """Why a task produced no result.

    Attributes:
        kind: "crashed" (the process died), "timeout", or "exception".
        message: what happened, in a user's words.
    """

    kind: str
    message: str


def _context() -> ForkServerContext | SpawnContext:
    if "forkserver" in multiprocessing.get_all_start_methods():
        context = multiprocessing.get_context("forkserver")
        context.set_forkserver_preload(PRELOAD)
        return context
    return multiprocessing.get_context("spawn")


def start_workers_early() -> None:
    """Start the forkserver now, so that its imports overlap the caller's own work (mesh
    loading); `run_tasks` would otherwise start it, and wait for it, on its first task."""
    if _context().get_start_method() == "forkserver":
        from multiprocessing import forkserver

        forkserver.ensure_running()


@contextmanager
def _main_module_hidden() -> Iterator[None]:
    """Start a worker without re-running the caller's main script in it.

    multiprocessing's forkserver and spawn re-import `__main__` in every child (by its
    file, or by its module name under `python -m`), so a script calling robotdesc at top
    level, without an `if __name__ == "__main__":` guard, would run again in each worker
    and fail there. The workers only run robotdesc's own functions, so while a worker is
    being started the main module's file and spec are hidden from that preparation step.
    """
    main = sys.modules.get("__main__")
    saved = {name: getattr(main, name) for name in ("__file__", "__spec__")
             if main is not None and hasattr(main, name)}
    try:
        if main is not None:
            if "__file__" in saved:
                del main.__file__
            if "__spec__" in saved:
                main.__spec__ = None
        yield
    finally:
        for name, value in saved.items():
            setattr(main, name, value)


def _child(function: Callable[[Any], Any], argument: Any, connection: _Pipe) -> None:
    try:
        try:
            result = function(argument)
        except BaseException as error:  # reported to the parent, which decides; not swallowed
            connection.send(("exception", f"{type(error).__name__}: {error}",
                             traceback.format_exc()))
        else:
            connection.send(("ok", result, ""))
    except (BrokenPipeError, EOFError):  # the parent is gone (terminated): nobody to tell
        pass
    connection.close()


def run_tasks(function: Callable[[Any], Any], arguments: Sequence[Any], *, jobs: int,
              timeout_s: float,
              on_done: Callable[[int, Any], None] | None = None) -> list[Any]:
    """Call `function(argument)` for each argument in isolated processes.

    Args:
        function: a module-level function (picklable by reference).
        arguments: one per task (picklable).
        jobs: processes at a time (at least 1).
        timeout_s: wall-clock limit of one task (s).
        on_done: called with (index, result or TaskFailure) as each task ends.

    Returns:
        Per argument, in order: the function's result or a `TaskFailure`.
    """
    context = _context()
    results: list[Any] = [None] * len(arguments)
    pending = list(range(len(arguments)))[::-1]
    running: dict[_Pipe, tuple[int, BaseProcess, _Pipe, float]] = {}
    try:
        while pending or running:
            while pending and len(running) < max(1, jobs):
                index = pending.pop()
                reader, writer = context.Pipe(duplex=False)
                process: BaseProcess = context.Process(
                    target=_child, args=(function, arguments[index], writer), daemon=True)
                with _main_module_hidden():
                    process.start()
                writer.close()
                running[reader] = (index, process, reader, time.monotonic())
            now = time.monotonic()
            deadline = min(start + timeout_s for _, _, _, start in running.values())
            ready = wait([*running.keys(), *(p.sentinel for _, p, _, _ in running.values())],
                         timeout=max(0.0, deadline - now))
            for reader in list(running):
                index, process, _, start = running[reader]
                outcome = _collect(reader, process, ready, start, timeout_s)
                if outcome is None:
                    continue
                del running[reader]
                results[index] = outcome
                if on_done is not None:
                    on_done(index, outcome)
    finally:
        for _, process, reader, _ in running.values():
            _stop(process)
            reader.close()
    return results


def _collect(reader: _Pipe, process: BaseProcess, ready: Sequence[object], start: float,
             timeout_s: float) -> Any | None:
    """The task's outcome when it has ended (or timed out), else None."""
    if reader in ready or process.sentinel in ready:
        try:
            if reader.poll():
                status, payload, trace = reader.recv()
                process.join(5)
                reader.close()
                if status == "ok":
                    return payload
                log.debug("worker exception:\n%s", trace)
                return TaskFailure("exception", payload)
        except (EOFError, OSError):
            pass
        process.join(5)
        reader.close()
        return TaskFailure("crashed", _death(process.exitcode))
    if time.monotonic() - start >= timeout_s:
        _stop(process)
        reader.close()
        return TaskFailure("timeout", f"did not finish within {timeout_s:g} s; stopped")
    return None


def _death(exitcode: int | None) -> str:
    if exitcode is not None and exitcode < 0:
        try:
            name = signal.Signals(-exitcode).name
        except ValueError:
            name = f"signal {-exitcode}"
        return f"the worker process was killed by {name}"
    return f"the worker process exited with code {exitcode} without a result"


def _stop(process: BaseProcess) -> None:
    if process.is_alive():
        process.kill()
    process.join(5)


def default_jobs() -> int:
    """All cores this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)
