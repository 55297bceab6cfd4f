"""The equivalent inertia box of a link, as Gazebo's inertia view draws it.

The box of uniform density with the link's mass and principal moments: for principal moments
I1, I2, I3 about principal axes e1, e2, e3, a box with edges a, b, c along those axes has
I1 = m (b^2 + c^2) / 12 and so on, hence a^2 = 6 (I2 + I3 - I1) / m. It sits at the centre of
mass, turned to the principal axes. Units: kg, m, kg*m^2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from robotdesc.model.elements import Inertial
from robotdesc.spatial import rpy_matrix


@dataclass(frozen=True, eq=False)
class InertiaBox:
    """The equivalent box of one link.

    Attributes:
        link: the link's name.
        transform: 4x4 box frame in the link frame (or world, once placed): origin at the
            centre of mass, axes along the principal axes (a proper rotation).
        size: full edge lengths along the box axes (m).
        mass: kg.
        moments: principal moments (kg*m^2) about the box axes, in axis order.
        valid: the moments satisfy the triangle inequality (a real body can have them); when
            not, the impossible edge is drawn with length 0.
    """

    link: str
    transform: np.ndarray
    size: tuple[float, float, float]
    mass: float
    moments: tuple[float, float, float]
    valid: bool

    def placed(self, link_pose: np.ndarray) -> InertiaBox:
        """The same box with its transform taken into the frame `link_pose` maps to."""
        return InertiaBox(self.link, link_pose @ self.transform, self.size, self.mass,
                          self.moments, self.valid)


def box_edges(mass: float, moments: tuple[float, float, float]) -> tuple[tuple[float, float,
                                                                                float], bool]:
    """Edge lengths (m) of the uniform box with `mass` (kg) and principal `moments`.

    Returns:
        ((a, b, c), valid): `valid` is False when a squared edge came out negative (the
        moments violate the triangle inequality) and was clamped to 0.
    """
    i1, i2, i3 = moments
    squares = (6.0 * (i2 + i3 - i1) / mass, 6.0 * (i1 + i3 - i2) / mass,
               6.0 * (i1 + i2 - i3) / mass)
    scale = max(abs(s) for s in squares) or 1.0
    valid = all(s >= -1e-9 * scale for s in squares)
    a, b, c = (math.sqrt(max(s, 0.0)) for s in squares)
    return (a, b, c), valid


def inertia_box(link: str, inertial: Inertial | None) -> InertiaBox | None:
    """The link-frame equivalent box, or None without a positive mass and a finite tensor."""
    if inertial is None or inertial.inertia is None or inertial.mass is None:
        return None
    mass = float(inertial.mass)
    tensor = np.array(inertial.inertia.matrix(), dtype=float)
    if not (mass > 0 and math.isfinite(mass)) or not np.all(np.isfinite(tensor)):
        return None
    values, vectors = np.linalg.eigh(tensor)
    if np.linalg.det(vectors) < 0:
        vectors[:, 2] = -vectors[:, 2]
    moments = (float(values[0]), float(values[1]), float(values[2]))
    size, valid = box_edges(mass, moments)
    valid = valid and moments[0] >= 0
    transform = np.identity(4)
    transform[:3, :3] = rpy_matrix(inertial.origin.rpy) @ vectors
    transform[:3, 3] = inertial.origin.xyz
    return InertiaBox(link, transform, size, mass, moments, valid)
