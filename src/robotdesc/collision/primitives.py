"""The best fitting box, cylinder, sphere or capsule per link, judged by volume overlap.

Candidates are fitted in the link geometry's minimum-volume oriented bounding box: each kind
covering every vertex (cylinders and capsules along each box axis), then shrunk to 90 % and
80 %. Each is judged by intersection over union (IoU) with the solid, computed exactly with
manifold3d booleans; the best wins. The solid is the mesh itself when it is a closed
manifold, else its convex hull (said in the notes).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from robotdesc.collision.hull import convex_hull
from robotdesc.collision.result import MeshPart, PrimitivePart
from robotdesc.collision.tessellate import SECTIONS
from robotdesc.model.elements import Box, Capsule, Cylinder, Pose, Sphere
from robotdesc.spatial import rotation_rpy

if TYPE_CHECKING:
    from manifold3d import Manifold

#: A fitted primitive's URDF geometry.
_Primitive = Box | Cylinder | Sphere | Capsule
SHRINK = (1.0, 0.9, 0.8)
#: Rotation taking a primitive's z axis onto the box axis 0, 1, 2.
_AXIS_ROTATIONS = (
    np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]]),  # about y by +90 deg
    np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]]),  # about x by -90 deg
    np.eye(3),
)


@dataclass(frozen=True)
class Fitted:
    """The chosen primitive and how well it overlaps the solid.

    Attributes:
        part: the primitive placed in the link frame.
        iou: intersection over union with the solid (0..1).
        tried: (kind, IoU) of the best candidate of each kind tried.
        notes: how the solid was obtained.
    """

    part: PrimitivePart
    iou: float
    tried: tuple[tuple[str, float], ...]
    notes: tuple[str, ...] = ()


def fit_primitive(vertices: np.ndarray, faces: np.ndarray,
                  kinds: tuple[str, ...]) -> Fitted:
    """Fit each kind in `kinds` and return the best by IoU.

    Raises:
        ImportError: manifold3d is not installed.
        robotdesc.errors.NoVolumeError: the mesh spans no volume.
    """
    import manifold3d  # noqa: F401  (ImportError before any work when it is missing)
    import trimesh

    hull = convex_hull(vertices)
    to_box, _ = trimesh.bounds.oriented_bounds(hull.vertices)  # type: ignore[no-untyped-call]
    box_from = np.linalg.inv(to_box)
    local = hull.vertices @ to_box[:3, :3].T + to_box[:3, 3]
    solid, notes = _solid(vertices @ to_box[:3, :3].T + to_box[:3, 3], faces,
                          hull, to_box)
    solid_volume = solid.volume()
    best: dict[str, tuple[float, _Primitive, np.ndarray, Manifold]] = {}
    for kind, geometry, rotation, shape in _candidates(local, kinds):
        inter = (solid ^ shape).volume()
        iou = inter / (solid_volume + shape.volume() - inter)
        if kind not in best or iou > best[kind][0]:
            best[kind] = (iou, geometry, rotation, shape)
    kind = max(best, key=lambda k: best[k][0])
    iou, geometry, rotation, _ = best[kind]
    link_rotation = box_from[:3, :3] @ rotation
    x, y, z = (float(v) for v in box_from[:3, 3])
    origin = Pose((x, y, z), rotation_rpy(link_rotation.tolist()))
    tried = tuple((k, round(float(v[0]), 4)) for k, v in best.items())
    return Fitted(PrimitivePart(geometry, origin), float(iou), tried, notes)


def _solid(local_vertices: np.ndarray, faces: np.ndarray, hull: MeshPart,
           to_box: np.ndarray) -> tuple[Manifold, tuple[str, ...]]:
    import manifold3d

    solid = manifold3d.Manifold(manifold3d.Mesh(
        vert_properties=np.ascontiguousarray(local_vertices, dtype=np.float32),
        tri_verts=np.ascontiguousarray(faces, dtype=np.uint32)))
    if solid.status() == manifold3d.Error.NoError and not solid.is_empty() \
            and solid.volume() > 0:
        return solid, ()
    hull_local = hull.vertices @ to_box[:3, :3].T + to_box[:3, 3]
    solid = manifold3d.Manifold.hull_points(np.ascontiguousarray(hull_local, dtype=np.float64))
    return solid, ("the mesh is not a closed manifold: primitives were judged against its "
                   "convex hull",)


def _candidates(local: np.ndarray, kinds: tuple[str, ...]
                ) -> Iterator[tuple[str, _Primitive, np.ndarray, Manifold]]:
    """(kind, URDF geometry, rotation box<-primitive, manifold solid) per candidate."""
    from manifold3d import Manifold

    half = np.abs(local).max(axis=0)
    for scale in SHRINK:
        if "box" in kinds:
            width, depth, height = (float(2 * h * scale) for h in half)
            size = (width, depth, height)
            yield "box", Box(size), np.eye(3), Manifold.cube(size, True)
        if "sphere" in kinds:
            radius = float(np.linalg.norm(local, axis=1).max() * scale)
            yield "sphere", Sphere(radius), np.eye(3), Manifold.sphere(radius, SECTIONS)
        for axis in range(3):
            others = [i for i in range(3) if i != axis]
            radial = np.linalg.norm(local[:, others], axis=1)
            along = np.abs(local[:, axis])
            rotation = _AXIS_ROTATIONS[axis]
            degrees = _degrees(axis)
            radius = float(radial.max())
            if "cylinder" in kinds:
                r, length = radius * scale, float(2 * along.max() * scale)
                shape = Manifold.cylinder(length, r, r, SECTIONS, True).rotate(degrees)
                yield "cylinder", Cylinder(r, length), rotation, shape
            if "capsule" in kinds:
                reach = np.sqrt(np.maximum(radius ** 2 - radial ** 2, 0.0))
                half_length = float(max(np.max(along - reach), 0.0))
                r, h = radius * scale, half_length * scale
                ends = [Manifold.sphere(r, SECTIONS).translate((0.0, 0.0, z)) for z in (-h, h)]
                shape = Manifold.batch_hull(ends).rotate(degrees)
                yield "capsule", Capsule(r, 2 * h), rotation, shape


def _degrees(axis: int) -> tuple[float, float, float]:
    """Euler rotation (degrees, manifold3d's x-then-y-then-z) matching _AXIS_ROTATIONS."""
    return ((0.0, 90.0, 0.0), (-90.0, 0.0, 0.0), (0.0, 0.0, 0.0))[axis]
