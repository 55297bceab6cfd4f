"""Findings of expensive rules remembered between runs.

Rules that build a Pinocchio model (needs "pinocchio") cost hundreds of milliseconds even
when nothing changed. Their findings depend only on the expanded document, the rule's
options, the mesh files the robot references and the versions of robotdesc and its
backends, so they are stored under a key made of exactly those (mesh files by path, size,
mtime and inode, as `make` would). Entries are written atomically and record their own
key; an entry stored under another key, not a regular file, larger than `MAX_ENTRY_BYTES` or
unreadable is a miss, never an error. `--no-cache` or `ROBOTDESC_CACHE_DIR=off` (a cache
folder of None) turns it off.
"""

from __future__ import annotations

import hashlib
import json
import logging
import os
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from robotdesc.code_stamp import code_id, module_stamp
from robotdesc.cache_dir import entry_file, read_entry, write_entry
from robotdesc.diagnostics import Finding, ValueChange
from robotdesc.rules.registry import Rule
from robotdesc.source import Provenance, Span

log = logging.getLogger(__name__)

#: A rule whose `needs` holds this is cached.
CACHED_NEED = "pinocchio"
_FORMAT = 2  # 2: the key inside the entry
#: The largest entry read (findings of one rule on one robot).
MAX_ENTRY_BYTES = 16 << 20


#: A mesh file as the key sees it: path, size (bytes), mtime (ns), inode; None when missing.
FileStat = tuple[str, int | None, int | None, int | None]
#: A span as stored: path, line, column.
SpanRecord = list[str | int]
#: A stored finding (JSON object): message, element, fix, and where (span, macro stack).
FindingRecord = dict[str, str | None | list[SpanRecord | list[SpanRecord]]
                     | list[list[str | float]]]


def is_cached(rule: Rule) -> bool:
    """Whether the rule's findings are cached (it builds a Pinocchio model)."""
    return CACHED_NEED in rule.needs


def rule_key(rule: Rule, options: object, document: bytes, mesh_files: Iterable[str],
             source: str = "") -> str:
    """The key of one rule's findings on one expanded document read from `source` (the
    findings point into it: two copies of one URDF have different keys); `options` enter
    by their repr."""

    stats: list[FileStat] = []
    for path in sorted(set(mesh_files)):
        try:
            info = os.stat(path)
            stats.append((path, info.st_size, info.st_mtime_ns, info.st_ino))
        except OSError:
            stats.append((path, None, None, None))
    material = json.dumps({"format": _FORMAT, "rule": rule.code, "options": repr(options),
                           "source": os.path.abspath(source) if source else "",
                           "document": hashlib.sha256(document).hexdigest(), "meshes": stats,
                           "versions": [code_id(), module_stamp("pinocchio"), module_stamp("coal")]})
    return hashlib.sha256(material.encode()).hexdigest()


def load(cache_dir: Path | None, key: str,
         sources: frozenset[str] | None = None) -> list[Finding] | None:
    """The cached findings, or None on a miss (or when the cache is off).

    Args:
        sources: the files of this run's description; an entry whose findings point
            anywhere else (a planted entry naming a secret file, whose lines a report
            would show) is a miss. None: not checked.
    """
    if cache_dir is None:
        return None
    raw = read_entry(entry_path(cache_dir, key), MAX_ENTRY_BYTES)
    if raw is None:
        return None
    try:
        data = json.loads(raw)
        if data["key"] != key:
            log.debug("rule cache: entry %s was stored under another key", key)
            return None
        findings = [_finding(item) for item in data["findings"]]
        if sources is not None and any(not _points_into(f, sources) for f in findings):
            log.debug("rule cache: entry %s points outside the description", key)
            return None
        return findings
    except (ValueError, KeyError, TypeError, IndexError) as exc:
        log.debug("rule cache: ignoring unreadable entry %s (%s)", key, exc)
        return None


def entry_path(cache_dir: Path, key: str) -> Path:
    """Where the rule cache keeps the entry of `key`."""
    return entry_file(cache_dir / "rules", key)


def store(cache_dir: Path | None, key: str, findings: list[Finding]) -> None:
    """Record one rule's findings under `key` (None: the cache is off)."""
    if cache_dir is None:
        return
    path = entry_path(cache_dir, key)
    folder = path.parent
    try:
        write_entry(path, json.dumps(
            {"key": key, "findings": [_record(f) for f in findings]}).encode("utf-8"))
    except OSError as exc:
        log.warning("rule cache: cannot write in %s (%s)", folder, exc)


def _span_record(span: Span) -> SpanRecord:
    return [span.path, span.line, span.col]


def _record(finding: Finding) -> FindingRecord:
    where = finding.where
    changes: list[list[str | float]] = [[c.element, c.attribute, c.value, c.tolerance]
                                        for c in finding.changes]
    spans: list[SpanRecord | list[SpanRecord]] | None = None if where is None else \
        [_span_record(where.span), [_span_record(s) for s in where.macro_stack]]
    return {"message": finding.message, "element": finding.element, "fix": finding.fix,
            "changes": changes, "unfixable": finding.unfixable, "where": spans}


def _points_into(finding: Finding, sources: frozenset[str]) -> bool:
    where = finding.where
    if where is None:
        return True
    return all(isinstance(span.path, str) and span.path in sources
               for span in (where.span, *where.macro_stack))


def _finding(item: dict[str, Any]) -> Finding:
    """A stored finding (JSON, read back: shapes checked by the callers' except clause)."""
    where = item["where"]
    provenance = None if where is None else Provenance(
        Span(*where[0]), tuple(Span(*s) for s in where[1]))
    changes = tuple(ValueChange(str(e), str(a), str(v), float(t))
                    for e, a, v, t in item.get("changes", []))
    return Finding(item["message"], provenance, item["element"], item["fix"], changes,
                   str(item.get("unfixable", "")))
