"""Fault injection for the worker tests: module-level, so a worker process can import it."""

from __future__ import annotations

import os
import signal

from robotdesc.collision.link import run_link


def crash_on_bad_link(task):
    """Like run_link, but the process dies by SIGSEGV on the link named 'bad'."""
    if task.link == "bad":
        os.kill(os.getpid(), signal.SIGSEGV)
    return run_link(task)


def sleep_forever(_argument):
    import time

    time.sleep(60)


def square(value):
    return value * value


def raise_error(_argument):
    raise RuntimeError("boom")


def stall_on_slow_link(task):
    """Like run_link, but the link named 'slow' never finishes."""
    if task.link == "slow":
        import time

        time.sleep(60)
    return run_link(task)


def write_pid_and_sleep(folder, seconds=60.0):
    """Write this worker's pid into `folder`, then sleep (a long link)."""
    import time

    with open(os.path.join(folder, f"{os.getpid()}.pid"), "w") as handle:
        handle.write("x")
    time.sleep(seconds)
    return os.getpid()


def write_pid_and_nap(folder):
    """A link that ends after 3 s, so it sends its result after its parent died."""
    return write_pid_and_sleep(folder, 3.0)
