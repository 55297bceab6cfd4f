"""`python -m robotdesc` and the `robotdesc` command (`run`)."""

import atexit
import gc
import os
import sys
import threading

from robotdesc.cli import main


def run() -> None:
    """Run the command line and end the process with its exit code.

    The process ends as Python would end it, less the teardown of its modules and objects
    (`_end`: 20-25 ms after a cold lint of TIAGo, 5 % of it). A young collection waits for
    more new objects than Python's default (`_COLLECTOR_THRESHOLDS`). `main` itself leaves
    the collector and the process alone: it may run inside a longer process.
    """
    gc.set_threshold(*_COLLECTOR_THRESHOLDS)
    _end(main())


def _end(code: int) -> None:
    """End this process with `code` once what Python does at exit that anyone can see is
    done: the atexit handlers run (a worker started early is killed, logging flushed) and
    stdout and stderr are flushed. The teardown after that (every module's objects freed,
    one by one) is skipped with `os._exit`. A thread that is not a daemon (Python would
    wait for it), or a profiler or tracer (cProfile, coverage: they write their data at
    exit), gets the ordinary exit, with every object left frozen first (`gc.freeze`: the
    collector does not walk the whole heap again while Python tears it down)."""
    if sys.getprofile() is not None or sys.gettrace() is not None or any(
            thread is not threading.main_thread() and not thread.daemon and thread.is_alive()
            for thread in threading.enumerate()):
        gc.freeze()
        sys.exit(code)
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a reader gone (`| head`) or a stream closed
            pass
    os._exit(code)


#: The collector's thresholds in a command's process: a young collection after 10,000 new
#: objects instead of 700 (a cold lint of TIAGo made 125 collections, about 0.03 s, with the
#: default; 8 with these); the older generations keep Python's ratios.
_COLLECTOR_THRESHOLDS = (10_000, 10, 10)


if __name__ == "__main__":
    run()
