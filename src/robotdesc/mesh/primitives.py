"""Analytic mass properties of URDF primitives at density 1 kg/m^3 (mass = volume).

Each is centred on its own frame's origin, as URDF places them; cylinders and capsules run
along z. Lengths in metres; inertia in kg*m^2 about the centre (for density 1, m^5).
"""

from __future__ import annotations

import math

from robotdesc.errors import GeometryError
from robotdesc.mesh.properties import MassProperties
from robotdesc.model.elements import Box, Capsule, Cylinder, Sphere

Primitive = Box | Cylinder | Sphere | Capsule


def box_properties(x: float, y: float, z: float) -> MassProperties:
    """A box of full edge lengths x, y, z (m)."""
    volume = x * y * z
    return _diagonal(volume, volume * (y * y + z * z) / 12, volume * (x * x + z * z) / 12,
                     volume * (x * x + y * y) / 12)


def cylinder_properties(radius: float, length: float) -> MassProperties:
    """A solid cylinder along z (m)."""
    volume = math.pi * radius * radius * length
    side = volume * (3 * radius * radius + length * length) / 12
    return _diagonal(volume, side, side, volume * radius * radius / 2)


def sphere_properties(radius: float) -> MassProperties:
    """A solid sphere (m)."""
    volume = 4.0 / 3.0 * math.pi * radius ** 3
    moment = 0.4 * volume * radius * radius
    return _diagonal(volume, moment, moment, moment)


def capsule_properties(radius: float, length: float) -> MassProperties:
    """A cylinder of `length` along z capped by two hemispheres of `radius` (m).

    Each hemisphere's centre of mass lies 3r/8 from its flat face; about it, its transverse
    moment is 83/320 m r^2 (moved to the capsule's centre with the parallel-axis theorem).
    """
    r, h = radius, length
    cylinder = math.pi * r * r * h
    cap = 2.0 / 3.0 * math.pi * r ** 3  # one hemisphere
    offset = h / 2 + 3 * r / 8
    side = (cylinder * (3 * r * r + h * h) / 12
            + 2 * (83.0 / 320.0 * cap * r * r + cap * offset * offset))
    axial = cylinder * r * r / 2 + 2 * (0.4 * cap * r * r)
    return _diagonal(cylinder + 2 * cap, side, side, axial)


def primitive_properties(geometry: Primitive) -> MassProperties:
    """Mass properties at density 1 of a URDF `<box>`, `<cylinder>`, `<sphere>` or `<capsule>`.

    Raises:
        GeometryError: a dimension is negative or not finite (also a ValueError).
    """
    if isinstance(geometry, Box):
        dims = tuple(geometry.size)
    elif isinstance(geometry, Sphere):
        dims = (geometry.radius,)
    else:
        dims = (geometry.radius, geometry.length)
    if not all(math.isfinite(d) and d >= 0 for d in dims):
        shape = type(geometry).__name__.lower()
        raise GeometryError(f"{shape} dimensions {dims} must be finite and not negative",
                            shape=shape, dimensions=tuple(float(d) for d in dims))
    if isinstance(geometry, Box):
        return box_properties(*dims)
    if isinstance(geometry, Sphere):
        return sphere_properties(*dims)
    if isinstance(geometry, Cylinder):
        return cylinder_properties(*dims)
    return capsule_properties(*dims)


def _diagonal(volume: float, ixx: float, iyy: float, izz: float) -> MassProperties:
    return MassProperties(volume, (0.0, 0.0, 0.0),
                          ((ixx, 0.0, 0.0), (0.0, iyy, 0.0), (0.0, 0.0, izz)), volume)
