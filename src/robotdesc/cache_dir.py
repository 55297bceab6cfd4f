"""Where robotdesc keeps its caches, and how an entry is read and written safely.

One switch turns every cache off for a run: `cache_folder(use_cache=False)` (what
`--no-cache` asks) is None, and so is the root when the environment says so.
The root: `$ROBOTDESC_CACHE_DIR` if set (an empty value, "0", "off", "none", "false" or
"no" turns every cache off), else `$XDG_CACHE_HOME/robotdesc`, else `~/.cache/robotdesc`.

An entry is used only when it is a regular file (opened without following a symlink and
without blocking, then checked with fstat: a FIFO, device or symlink is never read), no
larger than its cache's cap, sealed by this user's cache key, and (checked by each cache)
stored under the key asked for. Anything else is a miss: the value is recomputed and the
entry rewritten.

The seal: every entry starts with an HMAC-SHA256 of its bytes under a secret that is never
kept in the cache folder: `$ROBOTDESC_CACHE_KEY` when set (a CI secret shared by the jobs
that may share a cache), else 32 random bytes made once per user in
`$XDG_STATE_HOME/robotdesc/cache.key` (`~/.local/state/robotdesc/cache.key`, mode 0600).
A cache folder can be shared (a CI cache restored across branches, a folder others can
write): an entry written by anyone without the secret, or copied from another machine, is
a miss, never a result (docs/security.md, "Caches").
"""

from __future__ import annotations

import functools
import hashlib
import hmac
import logging
import os
import secrets
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


#: The first bytes of a sealed entry, before the HMAC's hex digits and a newline.
SEAL_PREFIX = b"robotdesc-seal-1 "
_SEAL_BYTES = len(SEAL_PREFIX) + 64 + 1


def key_path(env: Mapping[str, str] | None = None) -> Path:
    """Where this user's cache key is kept (never inside a cache folder)."""
    env = os.environ if env is None else env
    xdg = env.get("XDG_STATE_HOME", "").strip()
    base = Path(xdg) if xdg else Path(env.get("HOME") or str(Path.home())) / ".local" / "state"
    return base / "robotdesc" / "cache.key"


@functools.lru_cache(maxsize=None)
def _secret(configured: str | None, path: Path) -> bytes:
    """The secret entries are sealed with (see the module's docstring)."""
    if configured:
        return hashlib.sha256(configured.encode("utf-8")).digest()
    try:
        stored = read_regular_file(path, 256)
        if stored is None:
            path.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
            temporary = path.with_name(f"{path.name}.{os.getpid()}.{secrets.token_hex(4)}")
            handle = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
            try:
                os.write(handle, secrets.token_hex(32).encode())
            finally:
                os.close(handle)
            try:
                os.link(temporary, path)  # the first writer wins; the others read its key
            except FileExistsError:
                pass
            finally:
                os.unlink(temporary)
            stored = read_regular_file(path, 256)
        if stored is not None and len(stored.strip()) >= 32:
            return hashlib.sha256(stored.strip()).digest()
    except OSError as error:
        log.debug("no cache key at %s (%s): entries are sealed for this process only",
                  path, error)
    return secrets.token_bytes(32)


def _seal_of(data: bytes) -> bytes:
    secret = _secret(os.environ.get("ROBOTDESC_CACHE_KEY") or None, key_path())
    return hmac.new(secret, data, hashlib.sha256).hexdigest().encode()


def entry_file(folder: str | os.PathLike[str], key: str, suffix: str = ".json") -> Path:
    """Where a cache keeps the entry of `key` in its `folder`: in a subfolder named by the
    key's first two characters (a write lists its folder for stale temporaries: a few
    dozen entries, not thousands)."""
    return Path(folder) / key[:2] / f"{key}{suffix}"


def write_entry(path: str | os.PathLike[str], data: bytes) -> None:
    """Store a cache entry atomically, sealed (see the module's docstring).

    Raises:
        OSError: it could not be written (callers log and go on).
    """
    write_atomically(path, SEAL_PREFIX + _seal_of(data) + b"\n" + data)


def read_entry(path: str | os.PathLike[str], max_bytes: int) -> bytes | None:
    """The bytes of a cache entry written by `write_entry` under this user's key, or None:
    absent, not a regular file, over `max_bytes`, unsealed or sealed by another key."""
    raw = read_regular_file(path, max_bytes + _SEAL_BYTES)
    if raw is None or not raw.startswith(SEAL_PREFIX) or len(raw) < _SEAL_BYTES:
        return None
    seal, data = raw[len(SEAL_PREFIX):_SEAL_BYTES - 1], raw[_SEAL_BYTES:]
    if raw[_SEAL_BYTES - 1:_SEAL_BYTES] != b"\n" or not hmac.compare_digest(seal,
                                                                            _seal_of(data)):
        log.debug("%s not used: not sealed by this user's cache key", path)
        return None
    return data
