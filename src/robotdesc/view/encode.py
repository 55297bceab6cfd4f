"""The scene as the JSON document the page's viewer reads: metadata as plain JSON, vertex and
index arrays as base64 of little-endian float32 and uint16/uint32 (compact, and exact for
the float32 the GPU draws anyway)."""

from __future__ import annotations

import base64
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

from robotdesc.diagnostics import Diagnostic
from robotdesc.view.scene import Scene

FORMAT_VERSION = 1
COLLISION_COLOR = (0.95, 0.55, 0.12, 0.45)


def b64_array(values: np.ndarray, dtype: str) -> str:
    """Base64 of the array as little-endian `dtype` ("<f4", "<u2", "<u4")."""
    return base64.b64encode(np.ascontiguousarray(values, dtype=dtype).tobytes()).decode("ascii")


def _matrix(transform: np.ndarray) -> list[float]:
    """Column-major 4x4 (as WebGL wants), rounded to 0.1 um / 1e-7."""
    return [round(float(v), 7) for v in np.asarray(transform, dtype=float).T.ravel()]


def scene_document(scene: Scene, findings: Mapping[str, Iterable[Diagnostic]] | None = None,
                   title: str | None = None) -> dict[str, Any]:
    """The JSON-ready document of a scene.

    Args:
        scene: what to draw.
        findings: link name -> its lint diagnostics (highlighted in the view).
        title: the heading (default: the robot's name).
    """
    findings = findings or {}
    geometries = []
    for shape in scene.geometries:
        wide = len(shape.vertices) > 65535
        geometries.append({
            "label": shape.label, "faces": len(shape.faces),
            "source_faces": int(shape.source_faces), "primitive": shape.primitive,
            "positions": b64_array(shape.vertices, "<f4"),
            "indices": b64_array(shape.faces, "<u4" if wide else "<u2"),
            "index_type": "uint32" if wide else "uint16"})
    instances = [{"link": i.link, "kind": i.kind, "index": i.index, "geometry": i.geometry,
                  "matrix": _matrix(i.transform),
                  "color": [round(c, 4) for c in (i.color or COLLISION_COLOR)]}
                 for i in scene.instances]
    boxes = [{"link": b.link, "matrix": _matrix(b.transform),
              "size": [round(v, 7) for v in b.size], "mass": b.mass,
              "moments": list(b.moments), "valid": b.valid}
             for b in scene.inertia_boxes]
    visual = scene.faces_per_link("visual")
    collision = scene.faces_per_link("collision")
    links = []
    for name in scene.links:
        items = [{"code": d.code, "name": d.name, "severity": str(d.severity),
                  "message": d.message} for d in findings.get(name, ())]
        links.append({"name": name, "visual_faces": visual.get(name, 0),
                      "collision_faces": collision.get(name, 0), "findings": items})
    low, high = scene.bounds()
    return {"version": FORMAT_VERSION, "title": title or scene.robot, "robot": scene.robot,
            "source": scene.source,
            "configuration": {k: round(v, 6) for k, v in scene.configuration.items()},
            "bounds": [[round(float(v), 6) for v in low], [round(float(v), 6) for v in high]],
            "geometries": geometries, "instances": instances, "inertia_boxes": boxes,
            "links": links,
            "problems": [{"link": p.link, "kind": p.kind, "index": p.index,
                          "message": p.message} for p in scene.problems]}
