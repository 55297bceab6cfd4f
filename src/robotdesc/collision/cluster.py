"""Run tasks on a Dask cluster, with the same contract and isolation as worker.run_tasks.

Each argument becomes one Dask task. Inside the Dask worker the task still runs in its own
process (`worker.run_tasks` with one job), so a segfault or a stall in a native backend is a
`TaskFailure` for that task and the Dask worker lives on. Needs the optional extra
`robotdesc[dask]` here and robotdesc installed on every Dask worker.

Dask workers started by a nanny are daemonic processes, which Python's multiprocessing does
not let start children. For the duration of a task the worker process's daemon flag is
lifted: the task's child is itself daemonic, bounded by the timeout, and its forkserver exits
with the Dask worker.
"""

from __future__ import annotations

import asyncio
import logging
import multiprocessing
import threading
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from typing import Any

from robotdesc.collision.worker import TaskFailure, run_tasks
from robotdesc.errors import UsageError

log = logging.getLogger(__name__)

INSTALL_HINT = 'pip install ".[dask]"'

_daemon_lock = threading.Lock()
_daemon_users = 0
_daemon_was = False


def run_tasks_on_cluster(function: Callable[[Any], Any], arguments: Sequence[Any], *,
                         scheduler: str, timeout_s: float,
                         on_done: Callable[[int, Any], None] | None = None,
                         on_connect: Callable[[int], None] | None = None,
                         connect_timeout_s: float | None = None) -> list[Any]:
    """Call `function(argument)` for each argument on the Dask cluster at `scheduler`.

    Args:
        function: a module-level function (pickled by reference: importable on the workers).
        arguments: one per task (picklable).
        scheduler: the scheduler's address, e.g. "tcp://host:8786".
        timeout_s: wall-clock limit of one task once it runs on a worker (s); time queued
            on the cluster does not count.
        on_done: called with (index, result or TaskFailure) as each task ends.
        on_connect: called once connected, with the cluster's worker threads (the tasks
            that run at a time).
        connect_timeout_s: how long to try to reach the scheduler (s); default Dask's
            `distributed.comm.timeouts.connect` (30 s; env
            DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT).

    Returns:
        Per argument, in order: the function's result or a `TaskFailure`.

    Raises:
        UsageError: `distributed` is not installed, or no scheduler answers at `scheduler`.
    """
    distributed = _import_distributed()
    client = _connect(distributed, scheduler, connect_timeout_s)
    try:
        if on_connect is not None:
            on_connect(sum(client.nthreads().values()))
        # One submit per task: each message carries one link's meshes (one `map` would send
        # them all in a single graph), and the tasks queue until workers are there.
        futures = [client.submit(_isolated, function, argument, timeout_s, pure=False)
                   for argument in arguments]
        position = {future.key: index for index, future in enumerate(futures)}
        results: list[Any] = [None] * len(arguments)
        for future in distributed.as_completed(futures, loop=client.loop):
            index = position[future.key]
            outcome = _outcome(future, distributed)
            futures[index] = None  # released on the cluster once as_completed lets go too
            results[index] = outcome
            if on_done is not None:
                on_done(index, outcome)
        return results
    finally:
        client.close()


def _import_distributed() -> Any:
    try:
        import distributed
    except ImportError:
        raise UsageError("running on a Dask cluster needs the optional extra: "
                         f"{INSTALL_HINT}") from None
    return distributed


def _connect(distributed: Any, scheduler: str, timeout_s: float | None) -> Any:
    """A client of the scheduler at `scheduler`, or a UsageError naming the address."""
    if timeout_s is None:
        import dask

        timeout_s = dask.utils.parse_timedelta(
            dask.config.get("distributed.comm.timeouts.connect"), default="s")
    try:
        return distributed.Client(scheduler, timeout=timeout_s, set_as_default=False)
    except (OSError, TimeoutError, asyncio.TimeoutError) as error:
        raise UsageError(f"cannot reach the Dask scheduler at {scheduler}: {error}") from None
    except (ValueError, TypeError) as error:
        raise UsageError(f"not a Dask scheduler address: {scheduler!r} ({error})") from None


def _outcome(future: Any, distributed: Any) -> Any:
    """The task's result, or a TaskFailure when Dask itself could not run it."""
    try:
        return future.result()
    except distributed.KilledWorker as error:
        return TaskFailure("crashed", f"the Dask worker running it died: {error}")
    except Exception as error:  # e.g. the task could not be unpickled on the worker
        return TaskFailure("exception", f"on the Dask cluster: {type(error).__name__}: "
                                        f"{error}")


def _isolated(function: Callable[[Any], Any], argument: Any, timeout_s: float) -> Any:
    """Runs on a Dask worker: one task in its own process, as `run_tasks` does locally."""
    with _children_allowed():
        return run_tasks(function, [argument], jobs=1, timeout_s=timeout_s)[0]


@contextmanager
def _children_allowed() -> Iterator[None]:
    """Lift this process's daemon flag while any task of this process runs (thread-safe)."""
    global _daemon_users, _daemon_was
    process = multiprocessing.current_process()
    with _daemon_lock:
        if _daemon_users == 0:
            _daemon_was = process.daemon
            if _daemon_was:
                process.daemon = False
        _daemon_users += 1
    try:
        yield
    finally:
        with _daemon_lock:
            _daemon_users -= 1
            if _daemon_users == 0 and _daemon_was:
                process.daemon = True
