"""SHA-256 digests of files and bytes: the one way the caches and the collision manifest
recognise content."""

from __future__ import annotations

import hashlib
import os
import stat

_BLOCK = 1 << 20  # bytes read at a time

#: A file's identity as `lstat` gives it: (device, inode, size in bytes, modification time
#: and change time in ns). While it is the same, so is the content, except within the
#: timestamp granularity of a write (caches that trust it leave recently changed files out).
FileStamp = tuple[int, int, int, int, int]


def bytes_digest(data: bytes) -> str:
    """The SHA-256 of `data`, as hex."""
    return hashlib.sha256(data).hexdigest()


def file_digest(path: str, *, follow_symlinks: bool = True) -> str | None:
    """The SHA-256 of a regular file's bytes, as hex; None when it is missing, unreadable or
    not a regular file. Opened without blocking, so a FIFO put in a file's place never hangs;
    with `follow_symlinks=False` a symlink is refused as well (None)."""
    flags = os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC
    if not follow_symlinks:
        flags |= os.O_NOFOLLOW
    try:
        handle = os.open(path, flags)
    except OSError:
        return None
    try:
        if not stat.S_ISREG(os.fstat(handle).st_mode):
            return None
        digest = hashlib.sha256()
        while chunk := os.read(handle, _BLOCK):
            digest.update(chunk)
        return digest.hexdigest()
    except OSError:
        return None
    finally:
        os.close(handle)


def file_stamp(path: str) -> FileStamp | None:
    """The identity of a regular file that is no symlink (`lstat`), or None."""
    try:
        info = os.lstat(path)
    except OSError:
        return None
    if not stat.S_ISREG(info.st_mode):
        return None
    return _stamp(info)


def entry_stamp(path: str) -> FileStamp | None:
    """The identity of a folder entry of any kind, a symlink's own (`lstat`), or None when
    it is gone: a folder's changes when an entry is added, removed or renamed in it."""
    try:
        return _stamp(os.lstat(path))
    except OSError:
        return None


def _stamp(info: os.stat_result) -> FileStamp:
    return (info.st_dev, info.st_ino, info.st_size, info.st_mtime_ns, info.st_ctime_ns)
