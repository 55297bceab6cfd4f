"""Findings of expensive rules remembered between runs.

Rules that build a Pinocchio model (needs "pinocchio") cost hundreds of milliseconds even
when nothing changed. Their findings depend only on the expanded document, the rule's
options, the mesh files the robot references and the versions of robotdesc and its
backends, so they are stored under a key made of exactly those (mesh files by path, size,
mtime and inode, as `make` would). Entries are written atomically; an unreadable entry is a
miss, never an error. `--no-cache` turns it off.
"""

from __future__ import annotations

import hashlib
import json
import logging
import os
from pathlib import Path
from typing import Any, Iterable

from robotdesc.atomic import write_atomically
from robotdesc.diagnostics import Finding
from robotdesc.source import Provenance, Span

log = logging.getLogger(__name__)

#: A rule whose `needs` holds this is cached.
CACHED_NEED = "pinocchio"
_FORMAT = 1


def is_cached(rule: Any) -> bool:
    return CACHED_NEED in rule.needs


def rule_key(rule: Any, options: Any, document: bytes, mesh_files: Iterable[str],
             source: str = "") -> str:
    """The key of one rule's findings on one expanded document read from `source` (the
    findings point into it: two copies of one URDF have different keys)."""
    from importlib import metadata

    from robotdesc import __version__

    def version(name: str) -> str:
        try:
            return metadata.version(name)
        except metadata.PackageNotFoundError:
            return "none"

    stats = []
    for path in sorted(set(mesh_files)):
        try:
            info = os.stat(path)
            stats.append((path, info.st_size, info.st_mtime_ns, info.st_ino))
        except OSError:
            stats.append((path, None, None, None))
    material = json.dumps({"format": _FORMAT, "rule": rule.code, "options": repr(options),
                           "source": os.path.abspath(source) if source else "",
                           "document": hashlib.sha256(document).hexdigest(), "meshes": stats,
                           "versions": [__version__, version("pin"), version("coal")]})
    return hashlib.sha256(material.encode()).hexdigest()


def load(cache_dir: Path, key: str) -> list[Finding] | None:
    """The cached findings, or None on a miss."""
    try:
        data = json.loads((cache_dir / "rules" / f"{key}.json").read_text("utf-8"))
        return [_finding(item) for item in data]
    except FileNotFoundError:
        return None
    except (OSError, ValueError, KeyError, TypeError) as exc:
        log.debug("rule cache: ignoring unreadable entry %s (%s)", key, exc)
        return None


def store(cache_dir: Path, key: str, findings: list[Finding]) -> None:
    folder = cache_dir / "rules"
    try:
        write_atomically(folder / f"{key}.json",
                         json.dumps([_record(f) for f in findings]).encode("utf-8"))
    except OSError as exc:
        log.warning("rule cache: cannot write in %s (%s)", folder, exc)


def _span_record(span: Span) -> list:
    return [span.path, span.line, span.col]


def _record(finding: Finding) -> dict:
    where = finding.where
    return {"message": finding.message, "element": finding.element, "fix": finding.fix,
            "where": None if where is None else
            [_span_record(where.span), [_span_record(s) for s in where.macro_stack]]}


def _finding(item: dict) -> Finding:
    where = item["where"]
    provenance = None if where is None else Provenance(
        Span(*where[0]), tuple(Span(*s) for s in where[1]))
    return Finding(item["message"], provenance, item["element"], item["fix"])
