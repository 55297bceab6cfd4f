"""Mass properties of triangle meshes: the signed-tetrahedron volume integral over a soup.

Every triangle of a closed, outward-wound mesh spans a signed tetrahedron with a reference
point; summing their volume, first and second moments gives the solid's exactly (Tonon's
closed-form tetrahedron moments, summed as in Eberly's "Polyhedral Mass Properties").
The work is done in chunks of numpy arrays about the mesh's bounding-box centre (for
precision far from the origin).

Units: lengths in metres, volume m^3, mass kg, density kg/m^3, inertia kg*m^2 about the
centre of mass, expressed in the frame of the geometry.

Only the bulk integrals over triangles use numpy. The body they produce (`MassProperties`),
rigid transforms and sums are plain Python in `robotdesc.mesh.properties` (re-exported here).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from robotdesc.errors import GeometryError
from robotdesc.mesh.properties import MassProperties, combine, link_mass_properties
from robotdesc.spatial import Mat3, Vec3

__all__ = [
    "CHUNK_TRIANGLES",
    "MassProperties",
    "Mat3",
    "Vec3",
    "VolumeIntegrals",
    "bounds",
    "combine",
    "link_mass_properties",
    "reference_point",
    "volume_integrals",
]

#: Triangles per numpy chunk: large enough to amortise numpy's call overhead, small enough
#: for the temporaries to stay in cache.
CHUNK_TRIANGLES = 1 << 14


@dataclass(frozen=True)
class VolumeIntegrals:
    """The raw signed integrals of a triangle soup about a reference point.

    Attributes:
        reference: the point the integrals are taken about (m).
        values: integrals of 1, x, y, z, x^2, y^2, z^2, xy, yz, zx over the enclosed
            volume, coordinates relative to `reference` (m^3 .. m^5); signed: negative for
            an inward-wound (inverted) mesh.
    """

    reference: Vec3
    values: tuple[float, ...]

    @property
    def volume(self) -> float:
        """Signed volume (m^3)."""
        return self.values[0]

    def flipped(self) -> VolumeIntegrals:
        """The integrals of the same surface wound the other way (an inverted mesh fixed)."""
        return VolumeIntegrals(self.reference, tuple(-v for v in self.values))

    def properties(self) -> MassProperties:
        """Mass properties at density 1 kg/m^3; requires a positive volume.

        Raises:
            GeometryError: the signed volume is not positive (flip or repair first); also
                a ValueError.
        """
        v, sx, sy, sz, xx, yy, zz, xy, yz, zx = self.values
        if not v > 0:
            raise GeometryError(f"signed volume {v:g} m^3 is not positive", shape="mesh")
        cx, cy, cz = sx / v, sy / v, sz / v
        ixx = yy + zz - v * (cy * cy + cz * cz)
        iyy = zz + xx - v * (cz * cz + cx * cx)
        izz = xx + yy - v * (cx * cx + cy * cy)
        ixy = -(xy - v * cx * cy)
        iyz = -(yz - v * cy * cz)
        ixz = -(zx - v * cz * cx)
        inertia = ((ixx, ixy, ixz), (ixy, iyy, iyz), (ixz, iyz, izz))
        rx, ry, rz = self.reference
        return MassProperties(v, (cx + rx, cy + ry, cz + rz), inertia, v)


def volume_integrals(triangles: np.ndarray, chunk: int = CHUNK_TRIANGLES) -> VolumeIntegrals:
    """Integrate volume, first and second moments over the solid a triangle soup bounds.

    Args:
        triangles: (n, 3, 3) array of triangle vertices (m), wound counter-clockwise seen
            from outside; any float dtype (computed in float64).
        chunk: triangles per numpy chunk.

    Returns:
        The signed integrals about a reference point near the mesh (the mean of a sample of
        its vertices), which keeps the sums precise for meshes far from the origin.
    """
    reference = reference_point(triangles)
    sums = np.zeros(10)
    for start in range(0, len(triangles), chunk):
        part = np.asarray(triangles[start:start + chunk], dtype=np.float64) - reference
        sums += _chunk_integrals(part)
    weights = np.array([1 / 6] + [1 / 24] * 3 + [1 / 120] * 6)
    return VolumeIntegrals(_as_vec3(reference), tuple(float(v) for v in sums * weights))


def reference_point(triangles: np.ndarray, samples: int = 1024) -> np.ndarray:
    """The mean of up to `samples` evenly spaced vertices of the soup (m); cheap and inside
    the mesh's bounding box, which is all the integral needs for precision."""
    vertices = triangles.reshape(-1, 3)
    step = max(1, len(vertices) // samples)
    mean: np.ndarray = np.asarray(vertices[::step], dtype=np.float64).mean(axis=0)
    return mean


def bounds(triangles: np.ndarray, chunk: int = 1 << 18) -> tuple[Vec3, Vec3]:
    """Axis-aligned bounds (lower, upper corner) of a triangle soup (m).

    Reduced per chunk over contiguous coordinate columns: numpy's `min(axis=0)` on an
    (n, 3) array is an order of magnitude slower.
    """
    vertices = triangles.reshape(-1, 3)
    low = np.full(3, np.inf)
    high = np.full(3, -np.inf)
    for start in range(0, len(vertices), chunk):
        cols = np.ascontiguousarray(vertices[start:start + chunk].T)
        low = np.minimum(low, cols.min(axis=1))
        high = np.maximum(high, cols.max(axis=1))
    return _as_vec3(low), _as_vec3(high)


def _chunk_integrals(tri: np.ndarray) -> np.ndarray:
    """Unweighted sums of the per-tetrahedron terms for one chunk of (n, 3, 3) float64.

    Each triangle (p0, p1, p2) and the reference point span a tetrahedron of signed volume
    d / 6 with d = p0 . (p1 x p2). Over it, the integral of x is d * (x0 + x1 + x2) / 24 and
    the integral of x * y is d * (x0 y0 + x1 y1 + x2 y2 + sx * sy) / 120 with sx, sy the
    corner sums (Tonon, "Explicit exact formulas for the 3-D tetrahedron inertia tensor",
    2004). Plain elementwise numpy throughout: BLAS dot products of this size cost more in
    thread start-up than they save.
    """
    cols = np.ascontiguousarray(tri.transpose(2, 1, 0))  # [axis][corner][triangle]
    (x0, x1, x2), (y0, y1, y2), (z0, z1, z2) = cols
    d = x0 * (y1 * z2 - z1 * y2) + y0 * (z1 * x2 - x1 * z2) + z0 * (x1 * y2 - y1 * x2)
    sx, sy, sz = x0 + x1 + x2, y0 + y1 + y2, z0 + z1 + z2
    total = np.add.reduce
    return np.array([
        total(d),
        total(d * sx), total(d * sy), total(d * sz),
        total(d * (x0 * x0 + x1 * x1 + x2 * x2 + sx * sx)),
        total(d * (y0 * y0 + y1 * y1 + y2 * y2 + sy * sy)),
        total(d * (z0 * z0 + z1 * z1 + z2 * z2 + sz * sz)),
        total(d * (x0 * y0 + x1 * y1 + x2 * y2 + sx * sy)),
        total(d * (y0 * z0 + y1 * z1 + y2 * z2 + sy * sz)),
        total(d * (z0 * x0 + z1 * x1 + z2 * x2 + sz * sx)),
    ])


def _as_vec3(values: np.ndarray | Sequence[float]) -> Vec3:
    a, b, c = (float(v) for v in values)
    return (a, b, c)
