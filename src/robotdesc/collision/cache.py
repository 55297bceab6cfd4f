"""Link results cached by the hash of their sources and parameters.

`<cache dir>/collision-v<N>/<2 hex>/<key>.npz`: the geometry as arrays and the report as
JSON (with the key it was stored under), written atomically; an entry that is not a
regular file, is larger than `MAX_ENTRY_BYTES`, holds another key or is unreadable is
ignored and recomputed (see `robotdesc.cache_dir.read_regular_file`). A second run on
unchanged input does no decimation, decomposition or measurement. Bump CACHE_VERSION when a
method or a measurement changes.
"""

from __future__ import annotations

import io
import json
import logging
import os
from dataclasses import fields, replace
from pathlib import Path
from typing import Any

import numpy as np

from robotdesc.cache_dir import entry_file, read_entry, write_entry
from robotdesc.collision.result import Finding, LinkOutcome, LinkReport, MeshPart, PrimitivePart
from robotdesc.model.elements import Box, Capsule, Cylinder, Pose, Sphere

log = logging.getLogger(__name__)

CACHE_VERSION = 1
#: The largest entry read (the meshes of one link).
MAX_ENTRY_BYTES = 256 << 20
_PRIMITIVES = {"Box": Box, "Cylinder": Cylinder, "Sphere": Sphere, "Capsule": Capsule}


class CollisionCache:
    """Stored link outcomes (only successful ones: failures are retried every run)."""

    def __init__(self, directory: str | os.PathLike[str]) -> None:
        self.root = Path(directory) / f"collision-v{CACHE_VERSION}"

    def get(self, key: str) -> LinkOutcome | None:
        path = self._path(key)
        raw = read_entry(path, MAX_ENTRY_BYTES)
        if raw is None:
            return None
        try:
            with np.load(io.BytesIO(raw), allow_pickle=False) as data:
                meta = json.loads(str(data["meta"]))
                if meta.get("key") != key:
                    log.debug("collision cache entry %s holds another key", path)
                    return None
                outcome = _outcome(meta, data, "", key)
                alternatives = tuple(_outcome(m, data, f"a{j}_", key)
                                     for j, m in enumerate(meta.get("alternatives", ())))
        except (OSError, ValueError, KeyError, TypeError, AttributeError) as error:
            log.debug("ignoring unreadable collision cache entry %s: %s", path, error)
            return None
        return replace(outcome, alternatives=alternatives)

    def put(self, outcome: LinkOutcome) -> None:
        if not outcome.key or not outcome.parts:
            return
        arrays: dict[str, np.ndarray] = {}
        meta = _meta(outcome, arrays, "")
        meta["alternatives"] = [_meta(a, arrays, f"a{j}_")
                                for j, a in enumerate(outcome.alternatives)]
        arrays["meta"] = np.array(json.dumps(meta))
        buffer = io.BytesIO()
        # numpy's stub lets a name match `allow_pickle`, which older numpy does not have
        np.savez(buffer, **arrays)  # type: ignore[arg-type]
        path = self._path(outcome.key)
        try:
            write_entry(path, buffer.getvalue())
        except OSError as error:
            log.warning("collision cache not written to %s: %s", self.root, error)

    def _path(self, key: str) -> Path:
        return entry_file(self.root, key, ".npz")


def _report(data: dict[str, Any]) -> LinkReport:
    """A report read back from its `LinkReport.to_dict` JSON."""
    names = {f.name for f in fields(LinkReport)}
    values = {k: v for k, v in data.items() if k in names}
    values["findings"] = tuple(Finding(**f) for f in data.get("findings", ()))
    return LinkReport(**values)




def _meta(outcome: LinkOutcome, arrays: dict[str, np.ndarray], prefix: str) -> dict[str, Any]:
    """The JSON of one outcome; its meshes go into `arrays` under `prefix`."""
    meshes = [p for p in outcome.parts if isinstance(p, MeshPart)]
    primitives = [p for p in outcome.parts if isinstance(p, PrimitivePart)]
    for i, part in enumerate(meshes):
        arrays[f"{prefix}v{i}"] = part.vertices
        arrays[f"{prefix}f{i}"] = part.faces
    return {"key": outcome.key, "report": outcome.report.to_dict(),
            "convex": [p.convex for p in meshes],
            "primitives": [{"kind": type(p.geometry).__name__,
                            "dims": {k: v for k, v in vars(p.geometry).items()
                                     if k != "where"},
                            "xyz": list(p.origin.xyz), "rpy": list(p.origin.rpy)}
                           for p in primitives]}


def _outcome(meta: dict[str, Any], data: Any, prefix: str, key: str) -> LinkOutcome:
    """One outcome read back from `_meta`'s JSON and the arrays (KeyError, ValueError,
    TypeError: a corrupt entry)."""
    meshes = [MeshPart(data[f"{prefix}v{i}"], data[f"{prefix}f{i}"], bool(convex))
              for i, convex in enumerate(meta["convex"])]
    primitives = [PrimitivePart(_PRIMITIVES[p["kind"]](**p["dims"]),
                                Pose(tuple(p["xyz"]), tuple(p["rpy"])))
                  for p in meta["primitives"]]
    return LinkOutcome(_report(meta["report"]), tuple(meshes) + tuple(primitives), key)
