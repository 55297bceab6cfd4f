"""Talking to the worker process with bounded memory, and never leaving it behind.

`exchange` writes the job and reads the answer and the messages at once (no pipe can fill
and block either side), keeps at most `answer_cap` bytes of answer (past it the worker is
killed: a flood of output cannot grow the parent) and `MAX_MESSAGE_BYTES` of messages (the
rest is counted and dropped), and kills the worker's process group at the deadline.

`worker_group` makes sure the worker's group ends with the parent: whatever leaves the
block (an exception, Ctrl-C) kills it, and while the block runs in the main thread SIGTERM
and SIGHUP kill it before they take their usual effect on the parent. The worker also asks
the kernel for SIGKILL when its parent dies (`robotdesc.expansion.worker`), for the cases
no handler sees (SIGKILL of the parent).
"""

from __future__ import annotations

import contextlib
import logging
import os
import selectors
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from types import FrameType
from typing import IO

from robotdesc.atomic import deliver_signal
from robotdesc.expansion.launch import kill_group

log = logging.getLogger(__name__)

#: Bytes of the worker's messages (stderr) kept; the rest is counted and dropped.
MAX_MESSAGE_BYTES = 256 * 1024
_CHUNK = 1 << 16
#: What the worker's answer pipe holds (Linux, `F_SETPIPE_SZ`), and the most read at once:
#: with the default 64 KiB the worker waits for this process to read every 64 KiB of a
#: larger answer, each time this process's other thread (imports ahead, `robotdesc.linting`)
#: holds the interpreter lock.
_ANSWER_PIPE_BYTES = 1 << 20
#: The interpreter's switch interval while the worker runs (s; Python's default: 0.005):
#: this thread wakes for each piece of the answer, and while another thread of this process
#: computes (imports ahead, `robotdesc.linting`) it waits up to the interval each time to
#: get the interpreter back (a handful of times per answer).
_SWITCH_INTERVAL_S = 0.0005
#: Signals that end the parent and must take the worker with them.
_ENDING_SIGNALS = (signal.SIGTERM, signal.SIGHUP)


@dataclass(frozen=True)
class Exchanged:
    """What came back from the worker.

    Attributes:
        out: the answer (at most the cap).
        err: the first `MAX_MESSAGE_BYTES` of its messages.
        err_dropped: bytes of messages dropped past that.
        overflow: the answer passed the cap and the worker was killed.
        timed_out: the deadline passed and the worker was killed.
    """

    out: bytes
    err: bytes
    err_dropped: int = 0
    overflow: bool = False
    timed_out: bool = False


def exchange(proc: subprocess.Popen[bytes], job: bytes, timeout_s: float,
             answer_cap: int, while_waiting: Callable[[], object] | None = None) -> Exchanged:
    """Send `job` on the worker's stdin, collect stdout/stderr until it exits.

    Args:
        timeout_s: wall-clock seconds the worker may take before its group is killed.
        answer_cap: the most bytes of stdout kept before the worker is killed.
        while_waiting: called once the whole job is sent, in this thread, while the worker
            works (this process has nothing else to do then); the time it takes is not the
            worker's (the deadline moves by it).
    """
    assert proc.stdin is not None and proc.stdout is not None and proc.stderr is not None
    with _short_switch_interval():
        return _exchange(proc, job, timeout_s, answer_cap, while_waiting)


#: [the interval to restore, how many exchanges run] while any runs (threads of a server).
_SWITCH_STATE: list[float] = []
_SWITCH_LOCK = threading.Lock()


@contextlib.contextmanager
def _short_switch_interval() -> Iterator[None]:
    """`_SWITCH_INTERVAL_S` while at least one exchange of this process runs; the interval
    before the first one afterwards, whatever the order in which several end."""
    with _SWITCH_LOCK:
        if not _SWITCH_STATE:
            _SWITCH_STATE[:] = [sys.getswitchinterval(), 0]
            sys.setswitchinterval(min(_SWITCH_STATE[0], _SWITCH_INTERVAL_S))
        _SWITCH_STATE[1] += 1
    try:
        yield
    finally:
        with _SWITCH_LOCK:
            _SWITCH_STATE[1] -= 1
            if not _SWITCH_STATE[1]:
                sys.setswitchinterval(_SWITCH_STATE[0])
                _SWITCH_STATE.clear()


def _exchange(proc: subprocess.Popen[bytes], job: bytes, timeout_s: float,
              answer_cap: int, while_waiting: Callable[[], object] | None) -> Exchanged:
    assert proc.stdin is not None and proc.stdout is not None and proc.stderr is not None
    deadline = time.monotonic() + timeout_s
    out: list[bytes] = []
    err: list[bytes] = []
    out_size = err_size = dropped = 0
    pending = memoryview(job)
    _widen(proc.stdout)
    selector = selectors.DefaultSelector()
    os.set_blocking(proc.stdin.fileno(), False)
    selector.register(proc.stdin, selectors.EVENT_WRITE)
    selector.register(proc.stdout, selectors.EVENT_READ)
    selector.register(proc.stderr, selectors.EVENT_READ)
    try:
        while selector.get_map():
            left = deadline - time.monotonic()
            if left <= 0:
                kill_group(proc)
                return Exchanged(b"".join(out), b"".join(err), dropped, timed_out=True)
            for key, _ in selector.select(min(left, 1.0)):
                if key.fileobj is proc.stdin:
                    try:
                        written = os.write(proc.stdin.fileno(), pending[:_CHUNK])
                    except BrokenPipeError:
                        written = len(pending)
                    pending = pending[written:]
                    if not pending:
                        selector.unregister(proc.stdin)
                        proc.stdin.close()
                        if while_waiting is not None:
                            began = time.monotonic()
                            while_waiting()
                            deadline += time.monotonic() - began
                    continue
                fd = key.fileobj.fileno()  # type: ignore[union-attr]
                chunk = os.read(fd, _ANSWER_PIPE_BYTES if key.fileobj is proc.stdout else _CHUNK)
                if not chunk:
                    selector.unregister(key.fileobj)
                    continue
                if key.fileobj is proc.stdout:
                    out_size += len(chunk)
                    if out_size > answer_cap:
                        kill_group(proc)
                        return Exchanged(b"", b"".join(err), dropped, overflow=True)
                    out.append(chunk)
                else:
                    keep = max(0, MAX_MESSAGE_BYTES - err_size)
                    err.append(chunk[:keep])
                    err_size += min(len(chunk), keep)
                    dropped += len(chunk) - min(len(chunk), keep)
    finally:
        selector.close()
        for stream in (proc.stdin, proc.stdout, proc.stderr):
            with contextlib.suppress(OSError):
                stream.close()
    try:
        proc.wait(timeout=max(0.1, deadline - time.monotonic()))
    except subprocess.TimeoutExpired:
        kill_group(proc)
        return Exchanged(b"".join(out), b"".join(err), dropped, timed_out=True)
    return Exchanged(b"".join(out), b"".join(err), dropped)


def _widen(stream: IO[bytes]) -> None:
    """Let the pipe hold `_ANSWER_PIPE_BYTES` where the system allows (else it keeps its
    size: above /proc/sys/fs/pipe-max-size or a user's pipe quota, not Linux)."""
    import fcntl  # POSIX only

    setting = getattr(fcntl, "F_SETPIPE_SZ", None)
    if setting is None:
        return
    try:
        fcntl.fcntl(stream.fileno(), setting, _ANSWER_PIPE_BYTES)
    except OSError as error:
        log.debug("the worker's answer pipe keeps its size: %s", error)


class _Ended(BaseException):
    """A signal that ends the parent arrived while a worker ran."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


@contextlib.contextmanager
def worker_group(proc: subprocess.Popen[bytes]) -> Iterator[None]:
    """For the duration: the worker's group dies with the parent (see the module)."""
    previous: dict[int, object] = {}
    if threading.current_thread() is threading.main_thread():
        def end(signum: int, frame: FrameType | None) -> None:
            raise _Ended(signum)

        for signum in _ENDING_SIGNALS:
            try:
                old = signal.getsignal(signum)
                if old is signal.SIG_IGN:
                    continue
                previous[signum] = signal.SIG_DFL if old is None else old
                signal.signal(signum, end)
            except (ValueError, OSError):
                continue
    ended: int | None = None
    try:
        yield
    except _Ended as signalled:
        ended = signalled.signum
    finally:
        kill_group(proc)  # also what the worker left in its group (--trusted may fork)
        for number, handler in previous.items():
            signal.signal(number, handler)  # type: ignore[arg-type]
    if ended is not None:
        log.debug("signal %d: the xacro worker was killed with its group", ended)
        deliver_signal(ended, previous.get(ended))
