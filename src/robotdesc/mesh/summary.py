"""Summarize a loaded mesh: mass properties, bounds, health, and how the mass properties
were obtained when the surface is not a clean closed solid (numpy only).

Fallbacks, stated in `MeshSummary.method` and `notes`:
- closed and oriented (every edge run as often each way), positive volume: the exact
  integral ("exact");
- the same with negative volume (inverted, normals inward): the integral with the winding
  reversed ("flipped");
- open but consistently wound and manifold: each hole closed by a fan of triangles to the
  centroid of its boundary loop, then as above ("holes-capped"; exact for planar holes);
- otherwise (misoriented or non-manifold and open, or enclosing no volume): the convex
  hull of its vertices ("convex-hull"), an upper bound on the volume;
- no hull either (flat or collinear points): no mass properties ("none").
A negative or NaN mass is never produced.

The records (`MeshSummary`, `MassMethod`) live in `robotdesc.mesh.records` and reading a file
through the cache in `robotdesc.mesh.analyze`; both are re-exported here.
"""

from __future__ import annotations

from typing import TypedDict

import numpy as np

from robotdesc.mesh.health import MeshHealth, hole_caps, merge_vertices, mesh_health, topology
from robotdesc.mesh.hull import convex_hull_faces
from robotdesc.mesh.load import LoadedMesh
from robotdesc.mesh.mass import MassProperties, Vec3, VolumeIntegrals, bounds, volume_integrals
from robotdesc.mesh.records import MassMethod, MeshSummary

__all__ = ["FLAT_VOLUME_FRACTION", "MassMethod", "MeshSummary",
           "convex_hull_properties", "summarize"]


#: A closed mesh whose |signed volume| is below this fraction of its bounding box's is flat.
FLAT_VOLUME_FRACTION = 1e-9


class _Common(TypedDict):
    """The `MeshSummary` fields that do not depend on how the mass properties were found."""

    signed_volume: float
    bounds: tuple[Vec3, Vec3]
    health: MeshHealth
    unit_meter: float
    bodies: int
    broken_references: tuple[str, ...]


def summarize(mesh: LoadedMesh) -> MeshSummary:
    """Compute the summary of a loaded mesh (pure: no I/O)."""
    triangles = mesh.triangles
    topo = topology(triangles)
    health = mesh_health(triangles, topo)
    box = bounds(triangles)
    integrals = volume_integrals(triangles)
    signed = integrals.volume
    common: _Common = {"signed_volume": signed, "bounds": box, "health": health,
                       "unit_meter": mesh.unit_meter, "bodies": mesh.bodies,
                       "broken_references": mesh.broken_references}
    if health.encloses_volume and not _flat(signed, box):
        return _oriented(integrals, MassMethod.EXACT, (), common)
    if (health.boundary_edges and not health.misoriented_edges
            and not health.nonmanifold_edges):
        caps = hole_caps(topo)
        capped = volume_integrals(np.concatenate([triangles, caps]))
        if not _flat(capped.volume, box):
            note = (f"the surface is open ({health.boundary_edges} boundary edges in "
                    f"{health.hole_loops} loops); each hole was closed by a fan to its centroid")
            return _oriented(capped, MassMethod.HOLES_CAPPED, (note,), common)
    reason = _why_not_solid(health, _flat(signed, box))
    hull = convex_hull_properties(triangles)
    if hull is None:
        note = f"the surface {reason}, and its points span no volume: no mass properties"
        return MeshSummary(None, MassMethod.NONE, notes=(note,), **common)
    note = f"the surface {reason}; mass properties are those of its convex hull"
    return MeshSummary(hull, MassMethod.CONVEX_HULL, notes=(note,), **common)


def _oriented(integrals: VolumeIntegrals, method: MassMethod, notes: tuple[str, ...],
              common: _Common) -> MeshSummary:
    """The summary from integrals of a closed surface, reversing an inverted one."""
    if integrals.volume > 0:
        return MeshSummary(integrals.properties(), method, notes=notes, **common)
    note = (f"the surface is inverted (normals point inward, signed volume "
            f"{integrals.volume:.6g} m^3); its winding was reversed")
    return MeshSummary(integrals.flipped().properties(),
                       MassMethod.FLIPPED if method is MassMethod.EXACT else method,
                       notes=notes + (note,), **common)


def _flat(volume: float, box: tuple[Vec3, Vec3]) -> bool:
    diagonal = float(np.linalg.norm(np.subtract(box[1], box[0])))
    return abs(volume) <= FLAT_VOLUME_FRACTION * diagonal ** 3


def convex_hull_properties(triangles: np.ndarray) -> MassProperties | None:
    """Mass properties at density 1 of the convex hull of a soup's vertices (numpy's own
    quickhull, `robotdesc.mesh.hull`: no scipy), or None when the points span no volume
    (fewer than four distinct, or all coplanar or collinear)."""
    points, _ = merge_vertices(triangles)
    faces = convex_hull_faces(points)
    if faces is None:
        return None
    integrals = volume_integrals(points[faces])
    return integrals.properties() if integrals.volume > 0 else None


def _why_not_solid(health: MeshHealth, flat: bool) -> str:
    reasons = []
    if health.boundary_edges:
        reasons.append(f"is open ({health.boundary_edges} boundary edges)")
    if health.nonmanifold_edges:
        reasons.append(f"has {health.nonmanifold_edges} non-manifold edges")
    if health.misoriented_edges:
        reasons.append(f"is inconsistently wound ({health.misoriented_edges} edges)")
    if not reasons and health.unbalanced_edges:
        reasons.append(f"has {health.unbalanced_edges} edges run more often one way than "
                       "the other")
    if not reasons and flat:
        reasons.append("encloses no volume")
    return ", ".join(reasons)
