"""Collision geometry of each link, read with robotdesc's mesh core (no assimp, no ROS).

`collision_shapes` turns every `<collision>` into a `CollisionShape` (a primitive's sizes,
or a mesh's triangles in metres with its scale and COLLADA unit applied), placed in its
link's frame. Pure numpy apart from reading mesh files; `to_coal` makes coal objects.
"""

from __future__ import annotations

import functools
import logging
import os
from dataclasses import dataclass
from typing import Any

import numpy as np

from robotdesc.errors import MeshError
from robotdesc.kinematics.urdf_text import MeshPath
from robotdesc.model.elements import Box, Capsule, Cylinder, MeshRef, Robot, Sphere
from robotdesc.source import Provenance
from robotdesc.spatial import pose_matrix

log = logging.getLogger(__name__)


@dataclass(frozen=True, eq=False)
class CollisionShape:
    """One `<collision>` element.

    Attributes:
        link: the link it belongs to.
        index: its position among the link's `<collision>` elements.
        placement: 4x4 transform of the geometry frame in the link frame (m).
        kind: "box", "cylinder", "sphere", "capsule" or "mesh".
        size: box (x, y, z); cylinder and capsule (radius, length); sphere (radius,); m.
        triangles: for meshes, (n, 3, 3) vertex coordinates in the geometry frame (m).
        where: the `<collision>` element's provenance.
    """

    link: str
    index: int
    placement: np.ndarray
    kind: str
    size: tuple[float, ...] = ()
    triangles: np.ndarray | None = None
    where: Provenance | None = None

    def local_points(self) -> np.ndarray:
        """Points whose convex hull bounds the shape, in the geometry frame (k, 3), m."""
        if self.kind == "mesh":
            return self._mesh_vertices
        if self.kind == "box":
            half = np.asarray(self.size) / 2.0
        elif self.kind == "sphere":
            half = np.full(3, self.size[0])
        elif self.kind == "cylinder":
            half = np.array([self.size[0], self.size[0], self.size[1] / 2.0])
        else:  # capsule
            half = np.array([self.size[0], self.size[0], self.size[1] / 2.0 + self.size[0]])
        signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
        return signs * half

    @functools.cached_property
    def _mesh_vertices(self) -> np.ndarray:
        """The mesh's distinct vertices (computed once: a self-collision matrix asks for them
        at every sampled configuration, and sorting them is the costly part)."""
        assert self.triangles is not None  # a mesh shape always has its triangles
        vertices = np.unique(self.triangles.reshape(-1, 3), axis=0)
        vertices.setflags(write=False)
        return vertices

    def link_points(self) -> np.ndarray:
        """`local_points` in the link frame (k, 3), m."""
        points = self.local_points()
        placed: np.ndarray = points @ self.placement[:3, :3].T + self.placement[:3, 3]
        return placed


@dataclass(frozen=True)
class ShapeProblem:
    """A `<collision>` left out: why, and where."""

    link: str
    message: str
    where: Provenance | None = None


@functools.lru_cache(maxsize=256)
def _load_triangles(path: str, scale: tuple[float, float, float], mtime_ns: int,
                    size: int) -> np.ndarray:
    from robotdesc.mesh.load import load_mesh

    triangles = load_mesh(path, scale).triangles
    triangles.setflags(write=False)
    return triangles


def collision_shapes(robot: Robot, mesh_path: MeshPath) -> tuple[list[CollisionShape],
                                                                 list[ShapeProblem]]:
    """Every readable `<collision>` of the robot, and the ones left out with the reason."""
    shapes: list[CollisionShape] = []
    problems: list[ShapeProblem] = []
    for link in robot.links:
        for index, collision in enumerate(link.collisions):
            geometry, where = collision.geometry, collision.where or link.where
            placement = pose_matrix(collision.origin)
            if isinstance(geometry, Box):
                shapes.append(CollisionShape(link.name, index, placement, "box",
                                             tuple(geometry.size), where=where))
            elif isinstance(geometry, Sphere):
                shapes.append(CollisionShape(link.name, index, placement, "sphere",
                                             (geometry.radius,), where=where))
            elif isinstance(geometry, (Cylinder, Capsule)):
                kind = "cylinder" if isinstance(geometry, Cylinder) else "capsule"
                shapes.append(CollisionShape(link.name, index, placement, kind,
                                             (geometry.radius, geometry.length), where=where))
            elif isinstance(geometry, MeshRef):
                path = mesh_path(geometry)
                if path is None:
                    problems.append(ShapeProblem(link.name, f"mesh '{geometry.filename}' "
                                                 "does not resolve", where))
                    continue
                try:
                    stat = os.stat(path)
                    triangles = _load_triangles(path, tuple(geometry.scale), stat.st_mtime_ns,
                                                stat.st_size)
                except (MeshError, OSError) as error:
                    problems.append(ShapeProblem(link.name, f"mesh '{geometry.filename}' "
                                                 f"cannot be read: {error}", where))
                    continue
                shapes.append(CollisionShape(link.name, index, placement, "mesh",
                                             triangles=triangles, where=where))
    bad = [s for s in shapes if s.kind != "mesh"
           and not (all(np.isfinite(s.size)) and min(s.size, default=0.0) > 0.0)]
    for shape in bad:
        problems.append(ShapeProblem(shape.link, f"{shape.kind} sizes {shape.size} are not "
                                     "positive", shape.where))
    return [s for s in shapes if s not in bad], problems


def to_coal(shape: CollisionShape, convex: bool = False) -> Any:
    """A coal collision geometry for the shape (meshes: a BVH, or its convex hull)."""
    import coal

    if shape.kind == "box":
        return coal.Box(*shape.size)
    if shape.kind == "sphere":
        return coal.Sphere(shape.size[0])
    if shape.kind == "cylinder":
        return coal.Cylinder(shape.size[0], shape.size[1])
    if shape.kind == "capsule":
        return coal.Capsule(shape.size[0], shape.size[1])
    assert shape.triangles is not None  # a mesh shape always has its triangles
    vertices, faces = np.unique(shape.triangles.reshape(-1, 3), axis=0, return_inverse=True)
    faces = faces.reshape(-1, 3)
    bvh = coal.BVHModelOBBRSS()
    bvh.beginModel(len(faces), len(vertices))
    bvh.addVertices(np.ascontiguousarray(vertices))
    bvh.addTriangles(np.ascontiguousarray(faces, dtype=np.int64))
    bvh.endModel()
    if convex:
        bvh.buildConvexHull(True, "Qt")
        return bvh.convex
    return bvh
