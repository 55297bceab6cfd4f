"""Mass properties of solids: the signed-tetrahedron volume integral, rigid transforms, sums.

Every triangle of a closed, outward-wound mesh spans a signed tetrahedron with a reference
point; summing their volume, first and second moments gives the solid's exactly (Tonon's
closed-form tetrahedron moments, summed as in Eberly's "Polyhedral Mass Properties").
The work is done in chunks of numpy arrays about the mesh's bounding-box centre (for
precision far from the origin).

Units: lengths in metres, volume m^3, mass kg, density kg/m^3, inertia kg*m^2 about the
centre of mass, expressed in the frame of the geometry.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Iterable, Sequence

import numpy as np

Vec3 = tuple[float, float, float]
Mat3 = tuple[Vec3, Vec3, Vec3]

#: Triangles per numpy chunk: large enough to amortise numpy's call overhead, small enough
#: for the temporaries to stay in cache.
CHUNK_TRIANGLES = 1 << 14


@dataclass(frozen=True)
class MassProperties:
    """A rigid body's mass, centre of mass and inertia about the centre of mass.

    Attributes:
        mass: kg (for a solid of density 1 kg/m^3, equal to its volume in m^3).
        center_of_mass: m, in the frame of the geometry.
        inertia: 3x3 inertia tensor about the centre of mass (kg*m^2), rows of the matrix
            ((Ixx, Ixy, Ixz), (Ixy, Iyy, Iyz), (Ixz, Iyz, Izz)); products of inertia with the
            URDF sign convention (Ixy = -integral of x*y dm).
        volume: m^3 of the solid the mass was spread over.
    """

    mass: float
    center_of_mass: Vec3
    inertia: Mat3
    volume: float

    @property
    def density(self) -> float:
        """kg/m^3 (0 when the volume is 0)."""
        return self.mass / self.volume if self.volume > 0 else 0.0

    def inertia_matrix(self) -> np.ndarray:
        """The inertia tensor as a (3, 3) float array (kg*m^2)."""
        return np.array(self.inertia, dtype=float)

    def principal_moments(self) -> Vec3:
        """Eigenvalues of the inertia tensor, ascending (kg*m^2)."""
        values = np.linalg.eigvalsh(self.inertia_matrix())
        return (float(values[0]), float(values[1]), float(values[2]))

    def scaled_to_mass(self, mass: float) -> MassProperties:
        """The same solid with uniform density chosen so that its mass is `mass` (kg)."""
        factor = mass / self.mass if self.mass > 0 else 0.0
        return MassProperties(mass, self.center_of_mass,
                              _as_mat3(self.inertia_matrix() * factor), self.volume)

    def with_density(self, density: float) -> MassProperties:
        """The same solid at uniform `density` (kg/m^3)."""
        return self.scaled_to_mass(density * self.volume)

    def transformed(self, xyz: Sequence[float] = (0.0, 0.0, 0.0),
                    rpy: Sequence[float] = (0.0, 0.0, 0.0)) -> MassProperties:
        """The body expressed in a parent frame where its frame sits at `xyz`, `rpy`.

        Args:
            xyz: translation of the geometry frame in the parent frame (m).
            rpy: URDF roll-pitch-yaw of the geometry frame (rad): R = Rz(y) Ry(p) Rx(r).
        """
        rotation = rpy_matrix(rpy)
        center = rotation @ np.asarray(self.center_of_mass) + np.asarray(xyz, dtype=float)
        inertia = rotation @ self.inertia_matrix() @ rotation.T
        return MassProperties(self.mass, _as_vec3(center), _as_mat3(inertia), self.volume)


def rpy_matrix(rpy: Sequence[float]) -> np.ndarray:
    """URDF's rotation from roll, pitch, yaw (rad): R = Rz(yaw) @ Ry(pitch) @ Rx(roll)."""
    roll, pitch, yaw = (float(v) for v in rpy)
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return np.array([
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ])


def combine(bodies: Iterable[MassProperties]) -> MassProperties:
    """Sum rigid bodies given in one frame (parallel-axis theorem about the joint COM).

    Returns:
        The combined body; a zero body (mass 0, COM at the origin) when the sum has no mass.
    """
    parts = list(bodies)
    total = sum(p.mass for p in parts)
    volume = sum(p.volume for p in parts)
    if total <= 0:
        return MassProperties(0.0, (0.0, 0.0, 0.0), _as_mat3(np.zeros((3, 3))), volume)
    center = sum(p.mass * np.asarray(p.center_of_mass) for p in parts) / total
    inertia = np.zeros((3, 3))
    for p in parts:
        offset = np.asarray(p.center_of_mass) - center
        inertia += p.inertia_matrix() + p.mass * (offset @ offset * np.eye(3)
                                                  - np.outer(offset, offset))
    return MassProperties(total, _as_vec3(center), _as_mat3(inertia), volume)


def link_mass_properties(parts: Iterable[tuple[MassProperties, Sequence[float], Sequence[float]]],
                         mass: float | None = None) -> MassProperties:
    """Combine the geometries of one link in the link frame.

    Args:
        parts: (properties at density 1 in the geometry frame, origin xyz, origin rpy) per
            `<visual>` or `<collision>`.
        mass: the declared link mass (kg); None keeps density 1 kg/m^3.

    Returns:
        Uniform density over all parts, scaled to `mass` when given.
    """
    body = combine(p.transformed(xyz, rpy) for p, xyz, rpy in parts)
    return body.scaled_to_mass(mass) if mass is not None else body


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
            ValueError: when the signed volume is not positive (flip or repair first).
        """
        v, sx, sy, sz, xx, yy, zz, xy, yz, zx = self.values
        if not v > 0:
            raise ValueError(f"signed volume {v:g} m^3 is not positive")
        c = np.array([sx, sy, sz]) / v
        ixx = yy + zz - v * (c[1] ** 2 + c[2] ** 2)
        iyy = zz + xx - v * (c[2] ** 2 + c[0] ** 2)
        izz = xx + yy - v * (c[0] ** 2 + c[1] ** 2)
        ixy = -(xy - v * c[0] * c[1])
        iyz = -(yz - v * c[1] * c[2])
        ixz = -(zx - v * c[2] * c[0])
        inertia = ((ixx, ixy, ixz), (ixy, iyy, iyz), (ixz, iyz, izz))
        center = c + np.asarray(self.reference)
        return MassProperties(v, _as_vec3(center), tuple(tuple(float(x) for x in row)
                                                         for row in inertia), v)


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
    return np.asarray(vertices[::step], dtype=np.float64).mean(axis=0)


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


def _as_mat3(matrix: np.ndarray) -> Mat3:
    return (_as_vec3(matrix[0]), _as_vec3(matrix[1]), _as_vec3(matrix[2]))
