"""A file cache of mesh summaries, keyed by the mesh file's content hash and the scale.

Where: the cache root of `robotdesc.cache_dir` (`$ROBOTDESC_CACHE_DIR`, "off" turns it off,
else `$XDG_CACHE_HOME/robotdesc`, else `~/.cache/robotdesc`). Layout:

    <dir>/meshes-v<N>/<2 hex>/<sha256>.json   a summary (or a mesh error) per content + scale
    <dir>/stat-v<N>/<2 hex>/<sha256>.json     path -> (size, mtime, inode) -> content hash

The stat index lets a warm run skip reading and hashing unchanged files. Writes are atomic
(a temporary file renamed into place). Each entry records the key it was stored under (the
index: the path's hash) and is used only when that matches the key asked for; an entry
that is not a regular file, is larger than its cap, unreadable or corrupt is ignored (and
rewritten), never an error (see `robotdesc.cache_dir.read_regular_file`). Bump
`CACHE_VERSION` whenever loading or summarizing changes.

Plain Python (json, hashlib, no numpy): a warm run reads summaries without importing numpy.
"""

from __future__ import annotations

import hashlib
import json
import logging
import os
import stat
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from robotdesc.cache_dir import cache_root, entry_file, read_entry, write_entry
from robotdesc.digest import file_digest
from robotdesc.mesh.errors import MeshError, MeshErrorKind
from robotdesc.mesh.properties import MassProperties
from robotdesc.mesh.records import MassMethod, MeshHealth, MeshSummary

log = logging.getLogger(__name__)

CACHE_VERSION = 3  # 3: convex hulls by robotdesc.mesh.hull (numpy), not qhull
#: The largest entry read: a summary or an index record is a few kilobytes.
MAX_ENTRY_BYTES = 1 << 20
#: Errors that depend on the limits in force, not on the file alone: never cached.
_UNCACHED_ERRORS = {MeshErrorKind.TOO_LARGE, MeshErrorKind.UNREADABLE}


def default_cache_dir(env: Mapping[str, str] | None = None) -> Path | None:
    """The cache directory the environment asks for, or None when the cache is off."""
    return cache_root(env)


class MeshCache:
    """Summaries of mesh files on disk.

    Args:
        directory: where entries live (created on first write).
    """

    def __init__(self, directory: str | os.PathLike[str]) -> None:
        self.directory = Path(directory)
        # plain strings: these paths are built for every mesh of every warm run
        self._entries = os.path.join(self.directory, f"meshes-v{CACHE_VERSION}")
        self._stats = os.path.join(self.directory, f"stat-v{CACHE_VERSION}")
        self._write_failed = False

    def is_empty(self) -> bool:
        """No summary was ever stored here (every mesh is a miss: a first run, a fresh CI
        machine)."""
        try:
            with os.scandir(self._entries) as entries:
                return next(entries, None) is None
        except OSError:
            return True

    def key_for(self, path: str, scale: Sequence[float]) -> str | None:
        """The cache key of a file's content at a scale; None if the file cannot be read."""
        digest = self.content_digest(path)
        if digest is None:
            return None
        scale_text = ",".join(repr(float(s)) for s in scale)
        return hashlib.sha256(f"{digest}|{scale_text}".encode()).hexdigest()

    def content_digest(self, path: str) -> str | None:
        """SHA-256 of the file's bytes, served from the stat index when the file is unchanged."""
        try:
            info = os.stat(path)
        except OSError:
            return None
        if not stat.S_ISREG(info.st_mode):
            return None
        stamp = [info.st_size, info.st_mtime_ns, info.st_ctime_ns, info.st_ino]
        # abspath, not realpath: the stamp (with the inode) identifies the file, and
        # resolving symlinks would cost a stat per path component on every warm run.
        path_key = hashlib.sha256(os.path.abspath(path).encode()).hexdigest()
        index_file = entry_file(self._stats, path_key)
        known = _read_json(index_file)
        if isinstance(known, dict) and known.get("key") == path_key \
                and known.get("stamp") == stamp and isinstance(stored := known.get("digest"), str):
            return stored
        digest = file_digest(path)
        if digest is not None:
            self._write(index_file, {"key": path_key, "stamp": stamp, "digest": digest})
        return digest

    def get(self, key: str, path: str = "") -> MeshSummary | MeshError | None:
        """The stored summary (or mesh error) for `key`, or None when absent or corrupt."""
        data = _read_json(entry_file(self._entries, key))
        if not isinstance(data, dict):
            return None
        if data.get("key") != key:
            log.debug("mesh cache entry %s not used: stored under another key", key)
            return None
        try:
            if "error" in data:
                error = data["error"]
                return MeshError(MeshErrorKind(error["kind"]), str(error["detail"]), path)
            return summary_from_json(data["summary"])
        except (KeyError, TypeError, ValueError) as error:
            log.debug("ignoring corrupt mesh cache entry %s: %s", key, error)
            return None

    def put(self, key: str, summary: MeshSummary) -> None:
        """Store a summary (atomically; a failed write is logged once, not raised)."""
        self._write(entry_file(self._entries, key),
                    {"key": key, "summary": summary_to_json(summary)})

    def put_error(self, key: str, error: MeshError) -> None:
        """Store a mesh error that depends on the file's content alone."""
        if error.kind in _UNCACHED_ERRORS:
            return
        self._write(entry_file(self._entries, key),
                    {"key": key, "error": {"kind": error.kind.value, "detail": error.detail}})

    def _write(self, target: str | os.PathLike[str], data: Any) -> None:
        try:
            write_entry(target, json.dumps(data, separators=(",", ":")).encode("utf-8"))
        except OSError as error:
            if not self._write_failed:
                log.warning("mesh cache not written to %s: %s", self.directory, error)
                self._write_failed = True


def summary_to_json(summary: MeshSummary) -> dict[str, Any]:
    """A JSON-ready dict of a summary (floats kept exactly through repr round-trips)."""
    props = summary.properties
    return {
        "properties": None if props is None else {
            "mass": props.mass, "center_of_mass": list(props.center_of_mass),
            "inertia": [list(row) for row in props.inertia], "volume": props.volume},
        "method": summary.method.value,
        "signed_volume": summary.signed_volume,
        "bounds": [list(summary.bounds[0]), list(summary.bounds[1])],
        "health": vars(summary.health),
        "unit_meter": summary.unit_meter,
        "bodies": summary.bodies,
        "notes": list(summary.notes),
        "broken_references": list(summary.broken_references),
    }


def summary_from_json(data: dict[str, Any]) -> MeshSummary:
    """The inverse of `summary_to_json`.

    Raises:
        KeyError, TypeError, ValueError: the data is not a summary.
    """
    props = data["properties"]
    properties = None if props is None else MassProperties(
        float(props["mass"]), _vec3(props["center_of_mass"]),
        (_vec3(props["inertia"][0]), _vec3(props["inertia"][1]), _vec3(props["inertia"][2])),
        float(props["volume"]))
    return MeshSummary(
        properties=properties,
        method=MassMethod(data["method"]),
        signed_volume=float(data["signed_volume"]),
        bounds=(_vec3(data["bounds"][0]), _vec3(data["bounds"][1])),
        health=MeshHealth(**{k: int(v) for k, v in data["health"].items()}),
        unit_meter=float(data["unit_meter"]),
        bodies=int(data["bodies"]),
        notes=tuple(str(n) for n in data["notes"]),
        broken_references=tuple(str(n) for n in data.get("broken_references", ())),
    )


def _vec3(values: Sequence[Any]) -> tuple[float, float, float]:
    x, y, z = (float(v) for v in values)
    return (x, y, z)


def _read_json(path: str | os.PathLike[str]) -> Any:
    data = read_entry(path, MAX_ENTRY_BYTES)
    if data is None:
        return None
    try:
        return json.loads(data)
    except ValueError as error:
        log.debug("ignoring unreadable cache entry %s: %s", path, error)
        return None
