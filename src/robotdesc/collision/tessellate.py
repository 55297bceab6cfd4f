"""URDF primitives as triangle meshes (for measuring them, and for links whose visuals mix
primitives with meshes), and pose helpers. Lengths in metres, angles in radians."""

from __future__ import annotations

import math

import numpy as np

from robotdesc.collision.result import MeshPart
from robotdesc.model.elements import Box, Capsule, Cylinder, Pose, Sphere
from robotdesc.spatial import pose_matrix

#: Segments around a round primitive's axis (the error of the chord: 0.12 % of the radius).
SECTIONS = 64


def matrix_rpy(rotation: np.ndarray) -> tuple[float, float, float]:
    """URDF roll, pitch, yaw (rad) of a rotation matrix, R = Rz(yaw) Ry(pitch) Rx(roll)."""
    r = np.asarray(rotation, dtype=float)
    pitch = math.asin(max(-1.0, min(1.0, -r[2, 0])))
    if abs(r[2, 0]) < 1 - 1e-12:
        roll = math.atan2(r[2, 1], r[2, 2])
        yaw = math.atan2(r[1, 0], r[0, 0])
    else:  # gimbal lock: roll and yaw share one axis; put it all in yaw
        roll = 0.0
        yaw = math.atan2(-r[0, 1], r[1, 1])
    return (roll, pitch, yaw)


def primitive_mesh(geometry: Box | Cylinder | Sphere | Capsule,
                   origin: Pose | None = None) -> MeshPart:
    """A primitive as a closed, outward-wound triangle mesh placed by `origin`.

    Raises:
        ValueError: a dimension is not positive and finite.
    """
    import trimesh

    transform = pose_matrix(origin or Pose())
    if isinstance(geometry, Box):
        _check(geometry.size)
        mesh = trimesh.creation.box(extents=geometry.size, transform=transform)
    elif isinstance(geometry, Sphere):
        _check((geometry.radius,))
        mesh = trimesh.creation.icosphere(subdivisions=3, radius=geometry.radius)
        mesh.apply_transform(transform)
    elif isinstance(geometry, Cylinder):
        _check((geometry.radius, geometry.length))
        mesh = trimesh.creation.cylinder(radius=geometry.radius, height=geometry.length,
                                         sections=SECTIONS, transform=transform)
    else:
        _check((geometry.radius,))
        mesh = trimesh.creation.capsule(height=max(geometry.length, 0.0),
                                        radius=geometry.radius, count=[SECTIONS, SECTIONS // 2])
        mesh.apply_transform(transform)
    return MeshPart(np.asarray(mesh.vertices, dtype=np.float64),
                    np.asarray(mesh.faces, dtype=np.int64), convex=True)


def transform_points(matrix: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Apply a 4x4 transform to (n, 3) points."""
    return np.asarray(points) @ matrix[:3, :3].T + matrix[:3, 3]


def _check(dims: tuple[float, ...]) -> None:
    if not all(math.isfinite(d) and d > 0 for d in dims):
        raise ValueError(f"primitive dimensions {tuple(dims)} must be positive and finite")
