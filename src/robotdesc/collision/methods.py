"""The one table of collision methods: name, what it makes, the options it reads.

Import-free (no numpy), so that options, the command line and the docs read it cheaply; the
geometry of each method is `robotdesc.collision.link.MAKERS` (same names, checked by a test).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Method:
    """One collision method.

    Attributes:
        name: as given to `--method`.
        summary: what it makes, one line.
        fields: the `CollisionOptions` fields it reads (its part of the cache key).
    """

    name: str
    summary: str
    fields: tuple[str, ...]


_DECIMATE = ("ratio", "faces", "min_faces", "decimator", "adapt", "mesh_face_limit")
_HULL = ("adapt", "hull_vertex_limit")
_COACD = ("threshold", "max_hulls", "hull_vertices", "coacd_iterations", "coacd_depth",
          "coacd_nodes", "preprocess_resolution", "coacd_input_faces", "adapt",
          "hull_vertex_limit")
_PRIMITIVE = ("primitives",)

#: Every method, the default (auto) first.
METHOD_TABLE: tuple[Method, ...] = (
    Method("auto", "per link the cheapest to simulate of primitive, hull, CoACD pieces and "
           "decimations within a tolerance in the robot's scale, under a robot-wide "
           "triangle budget", tuple(dict.fromkeys(
               ("auto_order", "budget_triangles", "no_contact")
               + _DECIMATE + _HULL + _COACD + _PRIMITIVE))),
    Method("decimate", "one triangle mesh per link, its budget raised until --target is met",
           _DECIMATE),
    Method("hull", "one convex hull per link", _HULL),
    Method("coacd", "several convex hulls per link (CoACD)", _COACD),
    Method("primitive", "the best box, cylinder, sphere or capsule", _PRIMITIVE),
)
METHODS_BY_NAME = {m.name: m for m in METHOD_TABLE}
#: The default method.
DEFAULT_METHOD = "auto"
