"""The plain records of what robotdesc knows about one mesh file: its health, how its mass
properties were obtained, and its summary.

Plain Python (no numpy): the mesh cache rebuilds these from JSON on a warm run.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from robotdesc.mesh.properties import MassProperties, Vec3


@dataclass(frozen=True)
class MeshHealth:
    """What the edge counts say about a surface.

    Attributes:
        triangles: number of faces in the file (after triangulation).
        vertices: number of distinct vertex positions.
        degenerate_faces: faces with a repeated vertex or (almost) zero area.
        boundary_edges: edges used by one face only (holes: the mesh is open).
        nonmanifold_edges: edges used by more than two faces.
        misoriented_edges: edges shared by two faces that run them the same way (the
            winding flips there).
        unbalanced_edges: edges run more often one way than the other; zero exactly when
            the surface is a closed, oriented cycle whose enclosed volume is well defined
            (which a union of closed bodies touching along edges also is).
        hole_loops: connected groups of boundary edges (about the number of holes).
    """

    triangles: int
    vertices: int
    degenerate_faces: int
    boundary_edges: int
    nonmanifold_edges: int
    misoriented_edges: int
    unbalanced_edges: int = 0
    hole_loops: int = 0

    @property
    def watertight(self) -> bool:
        """Every edge is shared by exactly two faces (a closed two-manifold, as MeshLab asks)."""
        return self.boundary_edges == 0 and self.nonmanifold_edges == 0

    @property
    def consistent_winding(self) -> bool:
        """Neighbouring faces agree on orientation along every shared edge."""
        return self.misoriented_edges == 0

    @property
    def encloses_volume(self) -> bool:
        """The signed volume integral is exact (up to its overall sign) for this surface."""
        return self.unbalanced_edges == 0


class MassMethod(str, enum.Enum):
    """How a summary's mass properties were computed."""

    EXACT = "exact"
    FLIPPED = "flipped"
    HOLES_CAPPED = "holes-capped"
    CONVEX_HULL = "convex-hull"
    NONE = "none"


@dataclass(frozen=True)
class MeshSummary:
    """Mass properties, bounds and health of one mesh file at one scale.

    Attributes:
        properties: at density 1 kg/m^3 (mass = volume, m^3) in the mesh's own frame (m);
            None when no solid could be made of it (method NONE).
        method: how `properties` were obtained (the fallbacks are listed in
            `robotdesc.mesh.summary`).
        signed_volume: the volume the surface encloses as wound (m^3); negative when inverted.
        bounds: (lower, upper) corners of the axis-aligned bounding box (m).
        health: the surface's topology.
        unit_meter: the COLLADA unit factor applied (1.0 for other formats).
        bodies: number of geometries combined from the file.
        notes: the fallbacks taken, in a user's words.
        broken_references: material or texture references of the file that do not resolve
            (the geometry was read without them).
    """

    properties: MassProperties | None
    method: MassMethod
    signed_volume: float
    bounds: tuple[Vec3, Vec3]
    health: MeshHealth
    unit_meter: float = 1.0
    bodies: int = 1
    notes: tuple[str, ...] = ()
    broken_references: tuple[str, ...] = ()

    @property
    def extent(self) -> Vec3:
        """Size of the bounding box along x, y, z (m)."""
        low, high = self.bounds
        return (high[0] - low[0], high[1] - low[1], high[2] - low[2])
