"""A child process forked from this one that works beside it and answers on a pipe.

A cold lint leaves one core idle once the xacro worker has answered; the mesh summaries
(`robotdesc.mesh.prefetch`) and Pinocchio's verdict on the model
(`robotdesc.kinematics.verdict`) are computed there, by a fork of this process (its
imports and data come with it). The child runs only this process's own code on data this
process has; what it writes back is read like a cache entry all the same (shapes checked,
size capped), and a child that fails, ends early or writes nonsense only means the work is
done here. Linux only (`forks_here`), and only from a process with no other thread than
those that draw progress (`can_fork`: a fork copies no other thread, and a lock another
thread holds would stay held in the child).
"""

from __future__ import annotations

import ctypes
import gc
import logging
import os
import select
import signal
import sys
import threading
from collections.abc import Callable

log = logging.getLogger(__name__)

__all__ = ["Forked", "can_fork", "die_with_parent", "forks_here", "read_all", "write_all"]

#: Seconds a child may use no CPU while this process waits for it before it is taken for
#: stuck (a deadlock: a working child uses CPU; a child that waits for its inbox is not
#: counted until it has been given it).
STUCK_S = 30.0
#: How often a waiting read looks at the child's CPU time (s).
_POLL_S = 1.0
#: prctl's option that sends a signal to this process when its parent ends (Linux).
_PR_SET_PDEATHSIG = 1
_libc = ctypes.CDLL(None, use_errno=True) if sys.platform.startswith("linux") else None


def forks_here() -> bool:
    """Whether work can be shared with a forked child on this platform (Linux)."""
    return sys.platform.startswith("linux") and hasattr(os, "fork")


def can_fork() -> bool:
    """Whether this process may fork a child that runs Python now: `forks_here`, and no
    other thread but those that draw progress (they run none of the code the child runs, so
    no lock they hold can stop the child)."""
    return forks_here() and all(
        thread is threading.current_thread() or _draws_progress(thread)
        for thread in threading.enumerate())


def _draws_progress(thread: threading.Thread) -> bool:
    """robotdesc's progress lines (`robotdesc.progress`) and rich's bar refresh."""
    return thread.daemon and (thread.name.startswith("robotdesc-progress-")
                              or type(thread).__name__ == "_RefreshThread")


def die_with_parent(parent_pid: int) -> None:
    """Ask the kernel to SIGKILL this process when its parent ends (Linux; elsewhere the
    parent's handlers alone end it). Ends at once if the parent is already gone."""
    if _libc is not None:
        _libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    if os.getppid() != parent_pid:
        os._exit(1)


def write_all(fd: int, data: bytes) -> None:
    """Write all of `data` to the pipe `fd`."""
    while data:
        data = data[os.write(fd, data):]


class Forked:
    """A forked child running `work(inbox, out)`: `inbox` reads what this process `send`s
    (end of file once it has sent it, or closed), `out` writes to this process (`read`).
    The child ends with `os._exit(0)` when `work` returns or raises (nothing of this
    process's state is flushed or torn down twice), and when this process ends. This
    process's stdout and stderr are flushed before the fork; the child closes its copies of
    the pipes of this process's other children (so that each sees the end of its inbox), and
    never collects garbage (it is short-lived, and a collection would touch every object it
    shares with this process, copying their pages).

    Raises:
        OSError: no child could be forked.
    """

    def __init__(self, work: Callable[[int, int], None]) -> None:
        for stream in (sys.stdout, sys.stderr):  # else text buffered here is written twice
            try:
                stream.flush()
            except (OSError, ValueError):
                pass
        inbox_read, inbox_write = os.pipe()
        out_read, out_write = os.pipe()
        parent = os.getpid()
        try:
            pid = os.fork()
        except OSError:
            for fd in (inbox_read, inbox_write, out_read, out_write):
                os.close(fd)
            raise
        if pid == 0:  # the child: never returns
            try:
                for fd in (inbox_write, out_read, *_PARENT_ENDS):
                    os.close(fd)
                _PARENT_ENDS.clear()
                gc.disable()  # a collection would write to every object's page: copies
                die_with_parent(parent)
                signal.signal(signal.SIGINT, signal.SIG_DFL)
                signal.signal(signal.SIGTERM, signal.SIG_DFL)
                _quiet()
                work(inbox_read, out_write)
            finally:
                os._exit(0)
        os.close(inbox_read)
        os.close(out_write)
        self._pid, self._fd, self._inbox = pid, out_read, inbox_write
        _PARENT_ENDS.update((out_read, inbox_write))

    @property
    def running(self) -> bool:
        """Whether the child's answers may still come (its pipe is open here)."""
        return self._fd >= 0

    def send(self, data: bytes) -> None:
        """Give the child `data` on its inbox, then its end (once; later calls do nothing).
        A child that ended meanwhile is no error: its answer is missing when read."""
        if self._inbox < 0:
            return
        try:
            write_all(self._inbox, data)
        except OSError as error:  # BrokenPipeError: it ended
            log.debug("a forked child did not take its input: %s", error)
        self._close_inbox()

    def read(self, wait: bool, limit: int = 1 << 16) -> bytes | None:
        """What the child wrote since the last read, at most `limit` bytes: None when it
        wrote nothing yet (`wait`: wait until it writes or ends), b"" once it ended (or
        when this side was closed). A child that waits for nothing and has used no CPU for
        `STUCK_S` seconds while this process waits for it is stuck (it works, else): it is
        ended, and read as ended (this process does the work itself)."""
        if self._fd < 0:
            return b""
        if not wait:
            ready, _, _ = select.select([self._fd], [], [], 0)
            return os.read(self._fd, limit) if ready else None
        used, idle = _cpu_ticks(self._pid), 0.0
        while True:
            ready, _, _ = select.select([self._fd], [], [], _POLL_S)
            if ready:
                return os.read(self._fd, limit)
            now = _cpu_ticks(self._pid)
            idle = idle + _POLL_S if now == used and self._inbox < 0 else 0.0
            used = now
            if idle >= STUCK_S:
                log.warning("a helper process of robotdesc (pid %d) made no progress for %g s: "
                            "its work is done here instead", self._pid, STUCK_S)
                self.close()
                return b""

    def read_to_end(self, limit: int) -> bytes | None:
        """Everything the child writes until it ends (`read`, waiting); None past `limit`
        bytes."""
        data = b""
        while True:
            chunk = self.read(wait=True)
            if not chunk:
                return data
            data += chunk
            if len(data) > limit:
                return None

    def close(self) -> None:
        """End the child (when it still runs) and reap it."""
        self._close_inbox()
        if self._fd >= 0:
            _PARENT_ENDS.discard(self._fd)
            os.close(self._fd)
            self._fd = -1
        if self._pid:
            try:
                os.kill(self._pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            try:
                os.waitpid(self._pid, 0)
            except ChildProcessError:
                pass
            self._pid = 0

    def _close_inbox(self) -> None:
        if self._inbox >= 0:
            _PARENT_ENDS.discard(self._inbox)
            os.close(self._inbox)
            self._inbox = -1

    def __del__(self) -> None:
        self.close()


def _quiet() -> None:
    """In a child: Python's own output goes nowhere and nothing is logged. The parent's
    stdout and stderr objects are not touched again: a thread of the parent may have held
    their locks at the fork, and the child has no such thread to release them."""
    logging.disable(logging.CRITICAL)
    sys.stdout = sys.stderr = open(os.devnull, "w")  # noqa: SIM115 -- until os._exit


def _cpu_ticks(pid: int) -> int:
    """CPU time (user + system, clock ticks) process `pid` has used; -1 when unknown."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as stat:
            fields = stat.read().rsplit(b")", 1)[1].split()
        return int(fields[11]) + int(fields[12])
    except (OSError, IndexError, ValueError):
        return -1


def read_all(fd: int, limit: int) -> bytes | None:
    """Everything read from `fd` up to its end; None past `limit` bytes."""
    data = bytearray()
    while True:
        chunk = os.read(fd, 1 << 16)
        if not chunk:
            return bytes(data)
        data += chunk
        if len(data) > limit:
            return None


#: This process's ends of the pipes to its live children (closed in each new child).
_PARENT_ENDS: set[int] = set()
