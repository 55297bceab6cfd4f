"""The expansion cache: a repeated expansion of unchanged inputs skips xacro.

An entry is keyed by the top file, the arguments, the resolver and sandbox settings, the
allowed environment, and the versions of xacro (its installed file), robotdesc (its code)
and Python. It records the
SHA-256 of every file the expansion read; a lookup re-hashes them and misses when any
changed. Entries are written atomically and record their own key; an entry stored under
another key, not a regular file, larger than `MAX_ENTRY_BYTES` or unreadable is a miss,
never an error (see `robotdesc.cache_dir.read_regular_file`). A `cache_dir` of None
(caches off) reads and writes nothing.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import logging
import sys
from pathlib import Path
from typing import Any

from robotdesc.code_stamp import code_id, module_stamp
from robotdesc.cache_dir import entry_file, read_entry, write_entry
from robotdesc.digest import file_digest
from robotdesc.expansion.result import Expanded, MacroRecursion, ResolvedPackage, decode_input_facts
from robotdesc.source import Span

log = logging.getLogger(__name__)

_FORMAT = 6  # 2: declared_args and env_defaults; 3: the key inside; 4: passed values;
#              5: read_args; 6: the top file's digest in the key and among the inputs
#: The largest entry read (an expanded document of a very large robot is a few MB).
MAX_ENTRY_BYTES = 64 << 20


def _versions() -> dict[str, str]:
    return {"xacro": module_stamp("xacro"), "robotdesc": code_id(),
            "python": ".".join(map(str, sys.version_info[:3]))}


def cache_key(settings: dict[str, object]) -> str:
    """A hex digest of everything besides file contents that decides an expansion."""
    material = json.dumps({"format": _FORMAT, "versions": _versions(), **settings},
                          sort_keys=True, default=str)
    return hashlib.sha256(material.encode()).hexdigest()


def load(cache_dir: Path | None, key: str, top: str) -> Expanded | None:
    """The cached expansion for `key`, or None when absent, stale, unusable or off.

    A cache folder may be shared (a CI cache across branches) or planted, so an entry is
    believed only when it records the digests of its inputs, the top file `top` among them,
    every file its expansion names is one of them, and every one still matches. The caller
    then checks its paths against the roots of this run (`answer.check_expanded`).
    """
    if cache_dir is None:
        return None
    entry = entry_file(cache_dir / "expand", key)
    data = read_entry(entry, MAX_ENTRY_BYTES)
    if data is None:
        return None
    try:
        record = json.loads(data)
        if record["key"] != key:
            log.debug("expansion cache: %s was stored under another key", entry)
            return None
        inputs = record["inputs"]
        if not isinstance(inputs, dict) or not inputs or top not in inputs or not all(
                isinstance(p, str) and isinstance(d, str) for p, d in inputs.items()):
            log.debug("expansion cache: %s records no usable inputs", entry)
            return None
        expanded = _decode(record["expanded"])
        if expanded.source != top or not set(expanded.files) | set(expanded.files_read) \
                <= set(inputs) | {"<string>"}:
            log.debug("expansion cache: %s names files it did not record", entry)
            return None
        for path, digest in inputs.items():
            if file_digest(path) != digest:
                log.debug("expansion cache: %s changed", path)
                return None
        return expanded
    except Exception as exc:  # noqa: BLE001 -- any malformed entry is a miss, never an error
        log.debug("expansion cache: ignoring unreadable entry %s (%s)", entry, exc)
        return None


def store(cache_dir: Path | None, key: str, expanded: Expanded) -> None:
    """Record `expanded` under `key` with the digests of the files it read (None: off)."""
    if cache_dir is None:
        return
    inputs = {}
    for path in dict.fromkeys([expanded.source, *expanded.files, *expanded.files_read]):
        if path == "<string>":
            continue
        digest = file_digest(path)
        if digest is None:
            return  # an input vanished: do not cache
        inputs[path] = digest
    record = {"key": key, "inputs": inputs, "expanded": _encode(expanded)}
    entry = entry_file(cache_dir / "expand", key)
    try:
        write_entry(entry, json.dumps(record).encode("utf-8"))
    except OSError as exc:
        log.warning("expansion cache: cannot write %s (%s)", entry, exc)


def _encode(expanded: Expanded) -> dict[str, Any]:
    data = dataclasses.asdict(expanded)
    data["xml"] = expanded.xml.decode("utf-8")
    return data


def _decode(data: dict[str, Any]) -> Expanded:
    def span(value: dict[str, Any] | None) -> Span | None:
        return Span(**value) if value else None

    return Expanded(
        source=data["source"], xml=data["xml"].encode("utf-8"), files=tuple(data["files"]),
        files_read=tuple(data["files_read"]),
        packages=tuple(ResolvedPackage(**p) for p in data["packages"]),
        macro_recursion=tuple(MacroRecursion(m["macro"], m["depth"],
                                             span(m["defined_at"]) or Span(data["source"]),
                                             span(m["called_at"]))
                              for m in data["macro_recursion"]),
        from_xacro=data["from_xacro"], args=tuple(tuple(a) for a in data["args"]),
        **decode_input_facts(data))
