"""A robot as a display scene: every visual and collision geometry as a triangle mesh with
its world transform at a configuration, and each link's equivalent inertia box.

Primitives are tessellated; mesh files are resolved as the lint rules resolve them, loaded
through `robotdesc.mesh.load.load_mesh` (URDF scale applied) and reduced for display when
they exceed `max_faces`. A file used several times (left and right, 50 wheels) is stored
once. A mesh that cannot be shown is a `SceneProblem`, never an exception. Units: metres.
"""

from __future__ import annotations

import functools
import logging
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from robotdesc.errors import MeshError
from robotdesc.mesh.locate import MeshLocator
from robotdesc.model.elements import (
    Box,
    Capsule,
    Collision,
    Cylinder,
    Geometry,
    MeshRef,
    Robot,
    Sphere,
    Visual,
)
from robotdesc.model.tree import configuration, poses_at
from robotdesc.spatial import pose_matrix
from robotdesc.view.inertia_box import InertiaBox, inertia_box
from robotdesc.view.shapes import primitive_mesh
from robotdesc.view.simplify import reduce_faces, weld

log = logging.getLogger(__name__)

#: Faces one mesh may keep in a page (more are reduced for display only).
DEFAULT_MAX_FACES = 12_000
DEFAULT_COLOR = (0.72, 0.72, 0.75, 1.0)
KINDS = ("visual", "collision")


@dataclass(frozen=True, eq=False)
class SceneGeometry:
    """One distinct shape, in its own frame (URDF scale applied).

    Attributes:
        label: the mesh file's name, or the primitive and its dimensions.
        vertices: (V, 3) float32, m.
        faces: (F, 3) uint32 indices into `vertices`.
        source_faces: faces before the display reduction (of the mesh file, or of the
            primitive's tessellation).
        primitive: the shape is a URDF primitive, not a mesh file.
    """

    label: str
    vertices: np.ndarray
    faces: np.ndarray
    source_faces: int
    primitive: bool = False


@dataclass(frozen=True, eq=False)
class SceneInstance:
    """A geometry placed in the world.

    Attributes:
        link: the owning link.
        kind: "visual" or "collision".
        index: the element's position among the link's visuals (or collisions).
        geometry: index into `Scene.geometries`.
        transform: 4x4 world transform of the geometry frame.
        color: rgba 0..1 (the visual's material; None for collision geometry).
    """

    link: str
    kind: str
    index: int
    geometry: int
    transform: np.ndarray
    color: tuple[float, float, float, float] | None = None


@dataclass(frozen=True)
class SceneProblem:
    """A geometry that could not be shown, and why."""

    link: str
    kind: str
    index: int
    message: str


@dataclass(frozen=True, eq=False)
class Scene:
    """Everything a viewer draws.

    Attributes:
        robot: the robot's name.
        source: the description file.
        configuration: joint name -> value (rad or m) of every moving joint.
        links: link names in document order.
        link_poses: link name -> 4x4 world transform.
        geometries: distinct shapes.
        instances: placed shapes.
        inertia_boxes: equivalent inertia boxes, in world coordinates.
        problems: geometries left out.
    """

    robot: str
    source: str
    configuration: dict[str, float]
    links: tuple[str, ...]
    link_poses: dict[str, np.ndarray]
    geometries: tuple[SceneGeometry, ...]
    instances: tuple[SceneInstance, ...]
    inertia_boxes: tuple[InertiaBox, ...]
    problems: tuple[SceneProblem, ...] = field(default=())

    def faces_per_link(self, kind: str, source: bool = True) -> dict[str, int]:
        """Link name -> total faces of its `kind` geometry (before display reduction when
        `source`); links without such geometry are left out."""
        totals: dict[str, int] = {}
        for instance in self.instances:
            if instance.kind == kind:
                shape = self.geometries[instance.geometry]
                count = shape.source_faces if source else len(shape.faces)
                totals[instance.link] = totals.get(instance.link, 0) + count
        return totals

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """World axis-aligned bounds (lower, upper) of all instances and link origins (m)."""
        points = [pose[:3, 3] for pose in self.link_poses.values()]
        for instance in self.instances:
            shape = self.geometries[instance.geometry]
            if len(shape.vertices):
                low, high = shape.vertices.min(axis=0), shape.vertices.max(axis=0)
                corners = np.array([[x, y, z] for x in (low[0], high[0])
                                    for y in (low[1], high[1]) for z in (low[2], high[2])])
                points.extend(corners @ instance.transform[:3, :3].T + instance.transform[:3, 3])
        if not points:
            return np.zeros(3), np.zeros(3)
        stacked = np.asarray(points, dtype=float)
        return stacked.min(axis=0), stacked.max(axis=0)


def build_scene(robot: Robot, joint_values: Mapping[str, float] | None = None, *,
                meshes: MeshLocator | None = None, package_paths: tuple[str, ...] = (),
                package_map: tuple[tuple[str, str], ...] = (), max_faces: int = DEFAULT_MAX_FACES,
                kinds: tuple[str, ...] = KINDS) -> Scene:
    """The display scene of `robot` at a configuration.

    Args:
        robot: the parsed model.
        joint_values: joint name -> value (rad or m); other joints at their default.
        meshes: how `<mesh>` references are resolved (default: from `robot.source`).
        package_paths: folders searched for ROS packages first (when `meshes` is None).
        package_map: (package name, folder) pairs searched first (when `meshes` is None).
        max_faces: display budget per mesh file; larger meshes are reduced.
        kinds: which geometry to include ("visual", "collision").

    Raises:
        UsageError: `joint_values` names an unknown, fixed or mimic joint.
    """
    q = configuration(robot, joint_values)
    poses = poses_at(robot, q)
    files = meshes or MeshLocator.for_robot(robot, package_paths, package_map)
    builder = _GeometryStore(files, max_faces)
    instances: list[SceneInstance] = []
    problems: list[SceneProblem] = []
    boxes: list[InertiaBox] = []
    materials = {m.name: m.color for m in robot.materials if m.name and m.color}
    for link in robot.links:
        pose = poses[link.name]
        for kind in kinds:
            shapes: Sequence[Visual | Collision] = (link.visuals if kind == "visual"
                                                    else link.collisions)
            for index, shape in enumerate(shapes):
                found = builder.add(shape)
                if isinstance(found, str):
                    problems.append(SceneProblem(link.name, kind, index, found))
                    continue
                color = _color(shape, materials) if kind == "visual" else None
                instances.append(SceneInstance(link.name, kind, index, found,
                                               pose @ pose_matrix(shape.origin), color))
        box = inertia_box(link.name, link.inertial)
        if box is not None:
            boxes.append(box.placed(pose))
    for problem in problems:
        log.info("%s %s[%d] not shown: %s", problem.link, problem.kind, problem.index,
                 problem.message)
    return Scene(robot.name, robot.source, q, tuple(link.name for link in robot.links), poses,
                 tuple(builder.geometries), tuple(instances), tuple(boxes), tuple(problems))


#: A display shape's identity: ("mesh", resolved path, scale) or ("primitive", the class
#: name's repr, its dimensions).
_Key = tuple[str, str, tuple[object, ...]]


class _GeometryStore:
    """Distinct display shapes, keyed by mesh file and scale or by primitive."""

    def __init__(self, files: MeshLocator, max_faces: int) -> None:
        self.geometries: list[SceneGeometry] = []
        self._files = files
        self._max_faces = max_faces
        self._keys: dict[_Key, int | str] = {}

    def add(self, shape: Visual | Collision) -> int | str:
        """The index of the shape's geometry, or why it cannot be shown."""
        geometry = shape.geometry
        if geometry is None:
            return "the geometry element is missing or unreadable"
        if isinstance(geometry, MeshRef):
            resolution = self._files.locate(geometry)
            if not resolution.ok or resolution.path is None:
                return resolution.problem.message if resolution.problem else "not found"
            key: _Key = ("mesh", resolution.path, tuple(geometry.scale))
        else:
            key = ("primitive", repr(geometry.__class__.__name__),
                   tuple(v for k, v in vars(geometry).items() if k != "where"))
        if key not in self._keys:
            self._keys[key] = self._make(geometry, key)
        return self._keys[key]

    def _make(self, geometry: Geometry, key: _Key) -> int | str:
        if isinstance(geometry, MeshRef):
            try:
                status = os.stat(key[1])
                vertices, faces, source_faces = _display_mesh(
                    key[1], status.st_size, status.st_mtime_ns, tuple(geometry.scale),
                    self._max_faces)
            except MeshError as error:
                return f"{geometry.filename}: {error.detail}"
            except OSError as error:
                return f"{geometry.filename}: {error.strerror or error}"
            label = os.path.basename(key[1])
            primitive = False
        else:
            try:
                vertices, faces = primitive_mesh(geometry)
            except TypeError as error:
                return str(error)
            if not np.all(np.isfinite(vertices)):
                return f"{type(geometry).__name__.lower()} has non-finite dimensions"
            source_faces = len(faces)
            label = _primitive_label(geometry)
            primitive = True
        self.geometries.append(SceneGeometry(label, np.asarray(vertices, dtype=np.float32),
                                             np.asarray(faces, dtype=np.uint32),
                                             source_faces, primitive))
        return len(self.geometries) - 1


@functools.lru_cache(maxsize=256)
def _display_mesh(path: str, size: int, mtime_ns: int, scale: tuple[float, ...],
                  max_faces: int) -> tuple[np.ndarray, np.ndarray, int]:
    """A mesh file welded and reduced for display: (vertices, faces, faces of the file),
    kept per file state (`size` and `mtime_ns` key the cache only), so that a second view or
    report of the same robot does not simplify its meshes again."""
    from robotdesc.mesh.load import load_mesh

    loaded = load_mesh(path, scale)
    vertices, faces = weld(loaded.triangles)
    vertices, faces = reduce_faces(vertices, faces, max_faces)
    vertices, faces = np.asarray(vertices), np.asarray(faces)
    vertices.setflags(write=False)
    faces.setflags(write=False)
    return vertices, faces, len(loaded.triangles)


def _primitive_label(geometry: Box | Cylinder | Sphere | Capsule) -> str:
    values = {k: v for k, v in vars(geometry).items() if k != "where"}
    text = " ".join(f"{k}={'x'.join(f'{x:g}' for x in v) if isinstance(v, tuple) else f'{v:g}'}"
                    for k, v in values.items())
    return f"{type(geometry).__name__.lower()} {text}"


def _color(visual: Visual | Collision, materials: dict[str, tuple[float, float, float, float]]
           ) -> tuple[float, float, float, float]:
    material = getattr(visual, "material", None)
    if material is None:
        return DEFAULT_COLOR
    color = material.color or materials.get(material.name)
    if color is None or not all(np.isfinite(color)):
        return DEFAULT_COLOR
    red, green, blue, alpha = (float(min(max(c, 0.0), 1.0)) for c in color)
    return red, green, blue, alpha
