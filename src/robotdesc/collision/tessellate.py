"""URDF primitives as triangle meshes (for measuring them, and for links whose visuals mix
primitives with meshes), and placing points by a transform. Lengths in metres."""

from __future__ import annotations

import math

import numpy as np

from robotdesc.collision.result import MeshPart
from robotdesc.errors import GeometryError
from robotdesc.model.elements import Box, Capsule, Cylinder, Pose, Sphere
from robotdesc.spatial import pose_matrix

#: Segments around a round primitive's axis (the error of the chord: 0.12 % of the radius).
SECTIONS = 64


def primitive_mesh(geometry: Box | Cylinder | Sphere | Capsule,
                   origin: Pose | None = None) -> MeshPart:
    """A primitive as a closed, outward-wound triangle mesh placed by `origin`.

    Raises:
        GeometryError: a dimension is not positive and finite.
    """
    import trimesh

    transform = pose_matrix(origin or Pose())
    if isinstance(geometry, Box):
        _check("box", geometry.size)
        mesh = trimesh.creation.box(extents=geometry.size, transform=transform)
    elif isinstance(geometry, Sphere):
        _check("sphere", (geometry.radius,))
        mesh = trimesh.creation.icosphere(subdivisions=3, radius=geometry.radius)
        mesh.apply_transform(transform)
    elif isinstance(geometry, Cylinder):
        _check("cylinder", (geometry.radius, geometry.length))
        mesh = trimesh.creation.cylinder(radius=geometry.radius, height=geometry.length,
                                         sections=SECTIONS, transform=transform)
    else:
        _check("capsule", (geometry.radius,))
        mesh = trimesh.creation.capsule(height=max(geometry.length, 0.0),
                                        radius=geometry.radius, count=[SECTIONS, SECTIONS // 2])
        mesh.apply_transform(transform)
    return MeshPart(np.asarray(mesh.vertices, dtype=np.float64),
                    np.asarray(mesh.faces, dtype=np.int64), convex=True)


def transform_points(matrix: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Apply a 4x4 transform to (n, 3) points."""
    placed: np.ndarray = np.asarray(points) @ matrix[:3, :3].T + matrix[:3, 3]
    return placed


def _check(shape: str, dims: tuple[float, ...]) -> None:
    if not all(math.isfinite(d) and d > 0 for d in dims):
        raise GeometryError(f"primitive dimensions {tuple(dims)} must be positive and finite",
                            shape=shape, dimensions=tuple(float(d) for d in dims))
