"""Mass properties of rigid bodies and their per-link combination, in plain Python.

A link has a handful of geometries: moving each into the link frame (origin transform),
summing them (parallel-axis theorem), scaling to the declared mass and taking principal
moments is a few dozen multiplications, so it needs no numpy. Keeping it numpy-free lets a
warm lint (every mesh summary served from the cache) run without importing numpy at all.
The bulk triangle integrals that produce a mesh's properties live in `robotdesc.mesh.mass`.

Units: lengths in metres, volume m^3, mass kg, density kg/m^3, inertia kg*m^2 about the
centre of mass, expressed in the frame of the geometry.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from robotdesc.spatial import (
    ZERO,
    Mat3,
    Vec3,
    add,
    conjugated,
    parallel_axis,
    principal_moments,
    rotate,
    rpy_rotation,
    scaled,
    subtract,
    summed,
)

if TYPE_CHECKING:
    import numpy as np

__all__ = [
    "MassProperties",
    "Mat3",
    "Vec3",
    "combine",
    "link_mass_properties",
    "moved_bounds",
]


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
        """The inertia tensor as a (3, 3) float array (kg*m^2), for array code."""
        import numpy as np  # lazy: only callers that want an array pay for numpy

        return np.array(self.inertia, dtype=float)

    def principal_moments(self) -> Vec3:
        """Eigenvalues of the inertia tensor, ascending (kg*m^2)."""
        return principal_moments(self.inertia)

    def scaled_to_mass(self, mass: float) -> MassProperties:
        """The same solid with uniform density chosen so that its mass is `mass` (kg)."""
        factor = mass / self.mass if self.mass > 0 else 0.0
        return MassProperties(mass, self.center_of_mass, scaled(self.inertia, factor),
                              self.volume)

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
        if not any(xyz) and not any(rpy):
            return self  # the frames coincide (the usual `<origin>`)
        rotation = rpy_rotation(rpy)
        center = add(rotate(rotation, self.center_of_mass), [float(v) for v in xyz])
        return MassProperties(self.mass, center, conjugated(self.inertia, rotation),
                              self.volume)


def combine(bodies: Iterable[MassProperties]) -> MassProperties:
    """Sum rigid bodies given in one frame (parallel-axis theorem about the joint COM).

    Returns:
        The combined body; a zero body (mass 0, COM at the origin) when the sum has no mass.
    """
    parts = list(bodies)
    total = sum(p.mass for p in parts)
    volume = sum(p.volume for p in parts)
    if total <= 0:
        return MassProperties(0.0, (0.0, 0.0, 0.0), ZERO, volume)
    cx, cy, cz = (sum(p.mass * p.center_of_mass[i] for p in parts) / total for i in range(3))
    center = (cx, cy, cz)
    inertia = summed(parallel_axis(p.inertia, p.mass, subtract(p.center_of_mass, center))
                     for p in parts)
    return MassProperties(total, center, inertia, volume)


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


def moved_bounds(box: tuple[Sequence[float], Sequence[float]], xyz: Sequence[float],
                 rpy: Sequence[float]) -> tuple[Vec3, Vec3]:
    """Axis-aligned bounds (lower, upper corner, m) in the parent frame of a box given in a
    frame at `xyz`, `rpy` (its eight corners moved, then bounded)."""
    low, high = box
    rotation = rpy_rotation(rpy)
    offset = [float(v) for v in xyz]
    corners = [add(rotate(rotation, (x, y, z)), offset)
               for x in (low[0], high[0]) for y in (low[1], high[1]) for z in (low[2], high[2])]
    lower = (min(c[0] for c in corners), min(c[1] for c in corners), min(c[2] for c in corners))
    upper = (max(c[0] for c in corners), max(c[1] for c in corners), max(c[2] for c in corners))
    return lower, upper
