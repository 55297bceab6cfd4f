"""Atomic file replacement: a reader sees the old file or the new one, never a part of one.

The data goes to a temporary file beside the target, `.robotdesc-<name>.<pid>.<n>.tmp`,
which is then renamed over the target. The temporary is removed when the write fails or the
process gets SIGTERM or SIGINT during it (the signal then takes its usual course); one left
by SIGKILL names a process that no longer runs, and the next write of the same target
removes it. A new file gets mode 0666 minus the umask; a replaced file keeps its mode.

This is the low layer of `robotdesc.output` (user outputs) and of the caches.
"""

from __future__ import annotations

import contextlib
import itertools
import logging
import os
import signal
import stat
import threading
from collections.abc import Callable, Iterable, Iterator
from types import FrameType

log = logging.getLogger(__name__)

TEMP_PREFIX = ".robotdesc-"
TEMP_SUFFIX = ".tmp"
#: Bytes, or the chunks of a long output (written as they come).
Data = bytes | Iterable[bytes]

_counter = itertools.count()
_KEPT_MODE_BITS = 0o1777  # a replaced file keeps its permissions, never set-user/group-id


class _Signalled(BaseException):
    """SIGTERM or SIGINT arrived while a temporary file was open."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


def write_atomically(path: str | os.PathLike[str], data: Data, *, durable: bool = False) -> None:
    """Write `data` to `path` through a temporary file in the same folder and a rename.

    Creates the folder when missing. Leaves no temporary file behind, whatever fails,
    SIGTERM and SIGINT included.

    Args:
        path: the file to write (replaced when it exists; a symlink there is replaced too:
            `robotdesc.output.write_output` decides before calling this).
        data: the bytes, or an iterable of chunks.
        durable: fsync the file before the rename (user outputs; caches skip it).

    Raises:
        OSError: the folder or the file could not be written.
    """
    target = os.path.abspath(os.fspath(path))
    folder, name = os.path.split(target)
    os.makedirs(folder, exist_ok=True)
    remove_stale_temporaries(folder, name)
    try:
        mode = stat.S_IMODE(os.stat(target).st_mode) & _KEPT_MODE_BITS
    except OSError:
        mode = None  # new file: 0666 minus the umask, applied by open()
    temporary = os.path.join(folder, f"{TEMP_PREFIX}{name}.{os.getpid()}.{next(_counter)}"
                                     f"{TEMP_SUFFIX}")
    with _signals_remove(temporary):
        handle = _create(temporary)
        try:
            with os.fdopen(handle, "wb") as stream:
                if mode is not None:
                    os.fchmod(stream.fileno(), mode)
                for chunk in ([data] if isinstance(data, (bytes, bytearray, memoryview))
                              else data):
                    stream.write(chunk)
                if durable:
                    stream.flush()
                    os.fsync(stream.fileno())
            os.replace(temporary, target)
        finally:
            _unlink_quietly(temporary)


def remove_stale_temporaries(folder: str, name: str) -> int:
    """Remove the temporaries of `name` in `folder` whose process no longer runs (left by
    SIGKILL); returns how many were removed. Only regular files of exactly our naming."""
    prefix = f"{TEMP_PREFIX}{name}."
    removed = 0
    try:
        entries = [e for e in os.scandir(folder)
                   if e.name.startswith(prefix) and e.name.endswith(TEMP_SUFFIX)]
    except OSError:
        return 0
    for entry in entries:
        middle = entry.name[len(prefix):-len(TEMP_SUFFIX)].split(".")
        if len(middle) != 2 or not all(part.isdigit() for part in middle):
            continue
        pid = int(middle[0])
        try:
            if not entry.is_file(follow_symlinks=False) or _running(pid):
                continue
            os.unlink(entry.path)
            removed += 1
            log.debug("removed a stale temporary file %s", entry.path)
        except OSError:
            continue
    return removed


def _running(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # exists, owned by another user
        return True
    return True


def _create(temporary: str) -> int:
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC
    try:
        return os.open(temporary, flags, 0o666)
    except FileExistsError:  # left by a killed process that had our pid
        _unlink_quietly(temporary)
        return os.open(temporary, flags, 0o666)


def _unlink_quietly(path: str) -> None:
    try:
        os.unlink(path)
    except FileNotFoundError:
        pass
    except OSError as error:
        log.debug("cannot remove %s: %s", path, error)


@contextlib.contextmanager
def _signals_remove(temporary: str) -> Iterator[None]:
    """For the duration: SIGTERM/SIGINT abort the write (the caller's `finally` removes the
    temporary), then get their previous handling. Main thread only (elsewhere a no-op)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    # signal -> its handler before (what `signal.signal` takes back)
    previous: dict[int, Callable[[int, FrameType | None], object] | int | None] = {}

    def abort(signum: int, frame: object) -> None:
        raise _Signalled(signum)

    for signum in (signal.SIGTERM, signal.SIGINT):
        try:
            old = signal.getsignal(signum)
            if old is signal.SIG_IGN or old is None:
                continue
            previous[signum] = signal.signal(signum, abort)
        except (ValueError, OSError):
            continue
    caught: int | None = None
    try:
        yield
    except _Signalled as signalled:
        caught = signalled.signum
        log.debug("signal %d during the write of %s: temporary removed", caught, temporary)
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)
    if caught is not None:
        deliver_signal(caught, previous.get(caught))


def deliver_signal(signum: int, handler: object) -> None:
    """Give a caught signal its previous handling: a Python handler is called (SIGINT's
    default raises KeyboardInterrupt); the default action is taken by re-sending it."""
    if callable(handler):
        handler(signum, None)
        return
    os.kill(os.getpid(), signum)
    raise SystemExit(128 + signum)  # only reached if the signal did not end the process
