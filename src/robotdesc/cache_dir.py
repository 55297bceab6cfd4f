"""Where robotdesc keeps its caches, and how an entry is read and written safely.

One switch turns every cache off for a run: `cache_folder(use_cache=False)` (what
`--no-cache` asks) is None, and so is the root when the environment says so.
The root: `$ROBOTDESC_CACHE_DIR` if set (an empty value, "0", "off", "none", "false" or
"no" turns every cache off), else `$XDG_CACHE_HOME/robotdesc`, else `~/.cache/robotdesc`.

An entry is used only when it is a regular file (opened without following a symlink and
without blocking, then checked with fstat: a FIFO, device or symlink is never read), no
larger than its cache's cap, and (checked by each cache) stored under the key asked for.
Anything else is a miss: the value is recomputed and the entry rewritten.
"""

from __future__ import annotations

import logging
import os
import stat
from collections.abc import Mapping
from pathlib import Path

from robotdesc.atomic import write_atomically

log = logging.getLogger(__name__)

_OFF = {"", "0", "off", "none", "false", "no"}


def cache_root(env: Mapping[str, str] | None = None) -> Path | None:
    """The cache root the environment asks for (not created here), or None when caches are
    off."""
    env = os.environ if env is None else env
    if "ROBOTDESC_CACHE_DIR" in env:
        value = env["ROBOTDESC_CACHE_DIR"].strip()
        return None if value.lower() in _OFF else Path(value).expanduser()
    xdg = env.get("XDG_CACHE_HOME", "").strip()
    base = Path(xdg) if xdg else Path(env.get("HOME") or str(Path.home())) / ".cache"
    return base / "robotdesc"


def default_cache_dir() -> Path | None:
    """The cache root of this process's environment (None: caches are off)."""
    return cache_root()


def cache_folder(use_cache: bool = True,
                 explicit: str | os.PathLike[str] | None = None) -> Path | None:
    """The one cache switch: the folder every cache (expansion, meshes, rules, collision)
    reads and writes under, or None when caches are off (`--no-cache`, i.e. `use_cache`
    False, or `ROBOTDESC_CACHE_DIR=off`).

    Args:
        explicit: a folder given for this run (ExpandOptions.cache_dir), else the default.
    """
    if not use_cache:
        return None
    return Path(explicit) if explicit else default_cache_dir()


def read_regular_file(path: str | os.PathLike[str], max_bytes: int) -> bytes | None:
    """The bytes of a file robotdesc wrote earlier (a cache entry, a manifest), or None when
    it is absent, not a regular file (a symlink, FIFO or device is not followed or read),
    larger than `max_bytes`, or unreadable. Never blocks."""
    flags = os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC
    try:
        handle = os.open(path, flags)
    except FileNotFoundError:
        return None
    except OSError as error:  # ELOOP: a symlink; ENXIO: a FIFO's peer; EACCES ...
        log.debug("%s not used: %s", path, error)
        return None
    try:
        info = os.fstat(handle)
        if not stat.S_ISREG(info.st_mode):
            log.debug("%s not used: not a regular file", path)
            return None
        if info.st_size > max_bytes:
            log.debug("%s not used: %d bytes (cap %d)", path, info.st_size,
                      max_bytes)
            return None
        chunks, size = [], 0
        while size <= max_bytes:
            chunk = os.read(handle, min(1 << 20, max_bytes + 1 - size))
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
        if size > max_bytes:
            log.debug("%s not used: grew beyond the cap %d", path, max_bytes)
            return None
        return b"".join(chunks)
    except OSError as error:
        log.debug("%s not used: %s", path, error)
        return None
    finally:
        os.close(handle)


def write_entry(path: str | os.PathLike[str], data: bytes) -> None:
    """Store a cache entry atomically.

    Raises:
        OSError: it could not be written (callers log and go on).
    """
    write_atomically(path, data)
