"""The expansion cache: a repeated expansion of unchanged inputs skips xacro.

An entry is keyed by the top file, the arguments, the resolver and sandbox settings, the
allowed environment, and the versions of xacro, robotdesc and Python. It records the
SHA-256 of every file the expansion read; a lookup re-hashes them and misses when any
changed. Entries are written atomically; an unreadable entry is a miss, never an error.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import logging
import sys
from pathlib import Path

from robotdesc.atomic import write_atomically
from robotdesc.expansion.result import Expanded, ResolvedPackage
from robotdesc.rules.registry import MacroRecursion
from robotdesc.source import Span

log = logging.getLogger(__name__)

_FORMAT = 1


def _versions() -> dict[str, str]:
    from importlib import metadata

    def version(name: str) -> str:
        try:
            return metadata.version(name)
        except metadata.PackageNotFoundError:
            return "unknown"

    from robotdesc import __version__

    return {"xacro": version("xacro"), "robotdesc": __version__,
            "python": ".".join(map(str, sys.version_info[:3]))}


def cache_key(settings: dict) -> str:
    """A hex digest of everything besides file contents that decides an expansion."""
    material = json.dumps({"format": _FORMAT, "versions": _versions(), **settings},
                          sort_keys=True, default=str)
    return hashlib.sha256(material.encode()).hexdigest()


def file_digest(path: str) -> str | None:
    try:
        with open(path, "rb") as stream:
            return hashlib.file_digest(stream, "sha256").hexdigest() \
                if hasattr(hashlib, "file_digest") else hashlib.sha256(stream.read()).hexdigest()
    except OSError:
        return None


def _entry_path(cache_dir: Path, key: str) -> Path:
    return cache_dir / "expand" / key[:2] / f"{key}.json"


def load(cache_dir: Path, key: str) -> Expanded | None:
    """The cached expansion for `key`, or None when absent, stale or unreadable."""
    entry = _entry_path(cache_dir, key)
    try:
        record = json.loads(entry.read_text("utf-8"))
        for path, digest in record["inputs"].items():
            if file_digest(path) != digest:
                log.debug("expansion cache: %s changed", path)
                return None
        return _decode(record["expanded"])
    except FileNotFoundError:
        return None
    except (OSError, ValueError, KeyError, TypeError) as exc:
        log.debug("expansion cache: ignoring unreadable entry %s (%s)", entry, exc)
        return None


def store(cache_dir: Path, key: str, expanded: Expanded) -> None:
    """Record `expanded` under `key` with the digests of the files it read."""
    inputs = {}
    for path in dict.fromkeys([*expanded.files, *expanded.files_read]):
        digest = file_digest(path)
        if digest is None:
            return  # an input vanished: do not cache
        inputs[path] = digest
    record = {"inputs": inputs, "expanded": _encode(expanded)}
    entry = _entry_path(cache_dir, key)
    try:
        write_atomically(entry, json.dumps(record).encode("utf-8"))
    except OSError as exc:
        log.warning("expansion cache: cannot write %s (%s)", entry, exc)


def _encode(expanded: Expanded) -> dict:
    data = dataclasses.asdict(expanded)
    data["xml"] = expanded.xml.decode("utf-8")
    return data


def _decode(data: dict) -> Expanded:
    def span(value):
        return Span(**value) if value else None

    return Expanded(
        source=data["source"], xml=data["xml"].encode("utf-8"), files=tuple(data["files"]),
        files_read=tuple(data["files_read"]),
        packages=tuple(ResolvedPackage(**p) for p in data["packages"]),
        macro_recursion=tuple(MacroRecursion(m["macro"], m["depth"], span(m["defined_at"]),
                                             span(m["called_at"])) for m in data["macro_recursion"]),
        from_xacro=data["from_xacro"], args=tuple(tuple(a) for a in data["args"]))
