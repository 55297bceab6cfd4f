"""Triangle meshes of URDF primitives for display, in the geometry's own frame (m).

Each function returns (vertices (V, 3) float64, faces (F, 3) int64), wound counter-clockwise
seen from outside. Curved shapes use `segments` around their axis (z for cylinders and
capsules, as in URDF).
"""

from __future__ import annotations

import itertools

import numpy as np

from robotdesc.model.elements import Box, Capsule, Cylinder, Sphere

Mesh = tuple[np.ndarray, np.ndarray]
SEGMENTS = 24


def box_mesh(size: tuple[float, float, float]) -> Mesh:
    """A box of full edge lengths `size` (m), centred at the origin."""
    half = np.abs(np.asarray(size, dtype=float)) / 2
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
    faces = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5],   # -x, +x
                      [0, 4, 5], [0, 5, 1], [2, 3, 7], [2, 7, 6],   # -y, +y
                      [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])  # -z, +z
    return corners * half, faces


def _rings(profile: list[tuple[float, float]], segments: int) -> Mesh:
    """A surface of revolution about z from a (radius, z) profile listed bottom to top;
    profile points with radius 0 are single pole vertices."""
    angles = np.linspace(0.0, 2 * np.pi, segments, endpoint=False)
    cos, sin = np.cos(angles), np.sin(angles)
    vertices: list[np.ndarray] = []
    rings: list[list[int]] = []
    for radius, z in profile:
        start = sum(len(v) for v in vertices)
        if radius == 0.0:
            vertices.append(np.array([[0.0, 0.0, z]]))
            rings.append([start] * segments)
        else:
            vertices.append(np.column_stack([radius * cos, radius * sin, np.full(segments, z)]))
            rings.append(list(range(start, start + segments)))
    faces = []
    for lower, upper in itertools.pairwise(rings):
        for i in range(segments):
            j = (i + 1) % segments
            a, b, c, d = lower[i], lower[j], upper[j], upper[i]
            if a != b:
                faces.append((a, b, c))
            if c != d:
                faces.append((a, c, d))
    return np.concatenate(vertices), np.array(faces, dtype=np.int64)


def cylinder_mesh(radius: float, length: float, segments: int = SEGMENTS) -> Mesh:
    """A closed cylinder along z, centred at the origin (m)."""
    r, h = abs(radius), abs(length) / 2
    return _rings([(0.0, -h), (r, -h), (r, h), (0.0, h)], segments)


def sphere_mesh(radius: float, segments: int = SEGMENTS) -> Mesh:
    """A UV sphere about the origin (m)."""
    r = abs(radius)
    stacks = max(4, segments // 2)
    polar = np.linspace(np.pi, 0.0, stacks + 1)
    profile = [(0.0, -r)] + [(r * float(np.sin(t)), r * float(np.cos(t)))
                             for t in polar[1:-1]] + [(0.0, r)]
    return _rings(profile, segments)


def capsule_mesh(radius: float, length: float, segments: int = SEGMENTS) -> Mesh:
    """A cylinder of `length` along z capped by hemispheres of `radius` (m)."""
    r, h = abs(radius), abs(length) / 2
    quarter = max(2, segments // 4)
    bottom = [(r * float(np.sin(t)), -h - r * float(np.cos(t)))
              for t in np.linspace(0.0, np.pi / 2, quarter + 1)[1:]]
    top = [(r * float(np.cos(t)), h + r * float(np.sin(t)))
           for t in np.linspace(0.0, np.pi / 2, quarter + 1)[:-1]]
    return _rings([(0.0, -h - r)] + bottom + top + [(0.0, h + r)], segments)


def primitive_mesh(geometry: Box | Cylinder | Sphere | Capsule) -> Mesh:
    """The display mesh of any URDF primitive."""
    if isinstance(geometry, Box):
        return box_mesh(geometry.size)
    if isinstance(geometry, Cylinder):
        return cylinder_mesh(geometry.radius, geometry.length)
    if isinstance(geometry, Sphere):
        return sphere_mesh(geometry.radius)
    if isinstance(geometry, Capsule):
        return capsule_mesh(geometry.radius, geometry.length)
    raise TypeError(f"not a primitive: {type(geometry).__name__}")
