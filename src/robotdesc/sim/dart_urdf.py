"""A parsed robot -> the URDF text DART's loader reads: collision geometry only, every mesh a
file robotdesc resolved, every link's mass decided here.

DART reads meshes itself (through assimp) only from files, so:
- STL and OBJ meshes with a positive scale are handed over as the files robotdesc resolved
  (an absolute path: DART never looks a `package://` up);
- everything else (COLLADA with its units and node transforms, GLB/glTF, PLY, mirroring
  scales) and generated collision parts are loaded or made by robotdesc and written as binary
  STL files into a scratch directory that lives only while DART parses (DART keeps the meshes
  in memory);
- capsules (not URDF, not read by DART's loader) become a cylinder and two spheres.

Links without `<inertial>`: as libsdformat does for Gazebo, a link joined by a fixed joint is
massless and lumped into its parent; a moving link without mass is refused (Gazebo drops it
and everything below it; DART cannot integrate it), never silently given DART's 1 kg default.
"""

from __future__ import annotations

import logging
import os
from dataclasses import dataclass
from typing import Any, Mapping, Sequence

import numpy as np

from robotdesc.errors import SimMeshError, SimModelError
from robotdesc.model.elements import (
    Box,
    Capsule,
    Cylinder,
    Joint,
    Link,
    MeshRef,
    Pose,
    Robot,
    Sphere,
)
from robotdesc.model.tree import parent_joint_of
from robotdesc.sim.meshes import MeshAsset, MeshAssets
from robotdesc.spatial import rpy_matrix
from robotdesc.xml_text import quote_attribute

log = logging.getLogger(__name__)

#: Mesh files DART gets as they are (assimp reads them exactly as robotdesc does).
DIRECT_FORMATS = frozenset({"stl", "obj"})


@dataclass(frozen=True)
class DartUrdf:
    """The URDF DART parses and what it contains.

    Attributes:
        text: the URDF document.
        geoms: collision shapes of the robot.
        triangles: triangles of its collision meshes (primitives count none).
        mesh_files: the mesh files it refers to (resolved or scratch).
        mesh_geoms: the collision shapes that are meshes (the others are primitives).
    """

    text: str
    geoms: int
    triangles: int
    mesh_files: tuple[str, ...]
    mesh_geoms: int = 0


def dart_urdf(robot: Robot, meshes: MeshAssets, scratch: str,
              parts: Mapping[str, Sequence[Any]] | None = None,
              collision_from_visual: bool = False) -> DartUrdf:
    """The URDF text of `robot` for DART's loader.

    Args:
        robot: the parsed robot.
        meshes: resolves the robot's `<mesh>` references.
        scratch: a directory for meshes robotdesc converts (binary STL).
        parts: generated collision geometry per link (`MeshPart`/`PrimitivePart`).
        collision_from_visual: use the visual geometry as collision geometry.

    Raises:
        SimModelError: a moving link has no mass.
        SimMeshError: a mesh cannot be resolved or read.
    """
    writer = _Writer(meshes, scratch)
    moving_children = {name for name, joint in parent_joint_of(robot).items()
                       if joint.type != "fixed"}
    lines = [f"<robot name={quote_attribute(robot.name or 'robot')}>"]
    for link in robot.links:
        lines.append(f"  <link name={quote_attribute(link.name)}>")
        lines.extend(_inertial(link, link.name in moving_children))
        if parts is not None and link.name in parts:
            for index, part in enumerate(parts[link.name]):
                lines.extend(writer.part(link, index, part))
        else:
            shapes = link.visuals if collision_from_visual else link.collisions
            for shape in shapes:
                if shape.geometry is not None:
                    lines.extend(writer.shape(shape.origin, shape.geometry))
        lines.append("  </link>")
    for joint in robot.joints:
        lines.extend(_joint(joint))
    lines.append("</robot>")
    return DartUrdf("\n".join(lines) + "\n", writer.geoms, writer.triangles,
                    tuple(writer.files), writer.mesh_geoms)


def _inertial(link: Link, moving: bool) -> list[str]:
    inertial = link.inertial
    if inertial is None or inertial.mass is None or not inertial.mass > 0:
        if moving:
            raise SimModelError(f"link '{link.name}' moves but has no mass: Gazebo drops it "
                                "with everything below it, and DART cannot simulate it",
                                link.where.span if link.where else None, link.name)
        return []  # massless, lumped into its parent (DART: a zero-mass welded body)
    i = inertial.inertia
    values = (i.ixx, i.ixy, i.ixz, i.iyy, i.iyz, i.izz) if i is not None else (0.0,) * 6
    names = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    tensor = " ".join(f'{n}="{v!r}"' for n, v in zip(names, values))
    return ["    <inertial>", f"      {_origin(inertial.origin)}",
            f'      <mass value="{inertial.mass!r}"/>', f"      <inertia {tensor}/>",
            "    </inertial>"]


def _joint(joint: Joint) -> list[str]:
    lines = [f"  <joint name={quote_attribute(joint.name)} type={quote_attribute(joint.type)}>",
             f"    <parent link={quote_attribute(joint.parent)}/>",
             f"    <child link={quote_attribute(joint.child)}/>", f"    {_origin(joint.origin)}"]
    if joint.axis is not None:
        lines.append('    <axis xyz="%r %r %r"/>' % tuple(joint.axis))
    limit = joint.limit
    if limit is not None:
        values = {"lower": limit.lower, "upper": limit.upper, "effort": limit.effort,
                  "velocity": limit.velocity}
        text = " ".join(f'{k}="{v!r}"' for k, v in values.items() if v is not None)
        lines.append(f"    <limit {text}/>")
    if joint.dynamics is not None:
        values = {"damping": joint.dynamics.damping, "friction": joint.dynamics.friction}
        text = " ".join(f'{k}="{v!r}"' for k, v in values.items() if v is not None)
        lines.append(f"    <dynamics {text}/>")
    if joint.mimic is not None:
        mimic = joint.mimic
        lines.append(f"    <mimic joint={quote_attribute(mimic.joint)} "
                     f'multiplier="{mimic.multiplier if mimic.multiplier is not None else 1.0!r}" '
                     f'offset="{mimic.offset if mimic.offset is not None else 0.0!r}"/>')
    lines.append("  </joint>")
    return lines


def _origin(pose: Pose) -> str:
    return '<origin xyz="%r %r %r" rpy="%r %r %r"/>' % (*pose.xyz, *pose.rpy)


class _Writer:
    """Writes `<collision>` elements, converting meshes DART cannot take as they are."""

    def __init__(self, meshes: MeshAssets, scratch: str) -> None:
        self.meshes, self.scratch = meshes, scratch
        self.geoms = self.triangles = self.mesh_geoms = 0
        self.files: list[str] = []
        self._written: dict[tuple[str, tuple[float, ...]], tuple[str, int]] = {}

    def shape(self, origin: Pose, geometry: Any) -> list[str]:
        if isinstance(geometry, Capsule):
            return self._capsule(origin, geometry)
        if isinstance(geometry, MeshRef):
            path, scale, triangles = self._mesh_file(geometry)
            self.triangles += triangles
            self.mesh_geoms += 1
            inner = f"<mesh filename={quote_attribute(path)} scale=\"%r %r %r\"/>" % scale
        elif isinstance(geometry, Box):
            inner = '<box size="%r %r %r"/>' % tuple(max(s, 1e-6) for s in geometry.size)
        elif isinstance(geometry, Cylinder):
            inner = f'<cylinder radius="{geometry.radius!r}" length="{geometry.length!r}"/>'
        elif isinstance(geometry, Sphere):
            inner = f'<sphere radius="{geometry.radius!r}"/>'
        else:
            return []
        self.geoms += 1
        return ["    <collision>", f"      {_origin(origin)}",
                f"      <geometry>{inner}</geometry>", "    </collision>"]

    def part(self, link: Link, index: int, part: Any) -> list[str]:
        """A generated part: a mesh written as STL, or a primitive."""
        if not hasattr(part, "vertices"):
            return self.shape(getattr(part, "origin", Pose()), part.geometry)
        faces = np.asarray(part.faces, dtype=np.int64)
        path = os.path.join(self.scratch, f"generated_{len(self.files)}.stl")
        write_stl(path, np.asarray(part.vertices, dtype=float)[faces])
        self.files.append(path)
        self.geoms += 1
        self.mesh_geoms += 1
        self.triangles += len(faces)
        return ["    <collision>", f"      {_origin(Pose())}",
                f"      <geometry><mesh filename={quote_attribute(path)}/></geometry>",
                "    </collision>"]

    def _capsule(self, origin: Pose, capsule: Capsule) -> list[str]:
        axis = rpy_matrix(origin.rpy)[:, 2] * capsule.length / 2
        lines = self.shape(origin, Cylinder(capsule.radius, capsule.length))
        for sign in (1.0, -1.0):
            x, y, z = (float(v) for v in np.asarray(origin.xyz) + sign * axis)
            lines += self.shape(Pose((x, y, z)), Sphere(capsule.radius))
        return lines

    def _mesh_file(self, ref: MeshRef) -> tuple[str, tuple[float, float, float], int]:
        """(file, scale, triangles) of a mesh reference; converts when DART cannot read it."""
        asset = self.meshes.asset(ref)
        scale = (float(ref.scale[0]), float(ref.scale[1]), float(ref.scale[2]))
        key = (asset.source, scale)
        extension = os.path.splitext(asset.source)[1].lower().lstrip(".")
        if key in self._written:
            path, triangles = self._written[key]
            return path, (1.0, 1.0, 1.0) if path != asset.source else scale, triangles
        if extension in DIRECT_FORMATS and min(scale) > 0:
            triangles = _count_triangles(asset)
            self._written[key] = (asset.source, triangles)
            self.files.append(asset.source)
            return asset.source, scale, triangles
        soup = _triangle_soup(asset, ref)
        path = os.path.join(self.scratch, f"mesh_{len(self.files)}.stl")
        write_stl(path, soup)
        self.files.append(path)
        self._written[key] = (path, len(soup))
        return path, (1.0, 1.0, 1.0), len(soup)


def _count_triangles(asset: MeshAsset) -> int:
    """Triangles of a mesh file (binary STL: from its header; else loaded by robotdesc)."""
    if asset.faces is not None:
        return int(len(asset.faces))
    path = asset.source
    if path.lower().endswith(".stl"):
        size = os.path.getsize(path)
        with open(path, "rb") as handle:
            head = handle.read(84)
        if len(head) == 84:
            count = int.from_bytes(head[80:84], "little")
            if size == 84 + 50 * count:
                return count
    from robotdesc.mesh.load import load_mesh

    return int(len(load_mesh(path, (1.0, 1.0, 1.0)).triangles))


def _triangle_soup(asset: MeshAsset, ref: MeshRef) -> np.ndarray:
    """(n, 3, 3) triangles of a mesh in metres, scaled, with mirrored winding repaired."""
    from robotdesc.mesh.load import load_mesh
    from robotdesc.mesh.validate import MeshError

    scale = tuple(float(s) for s in ref.scale)
    try:
        triangles = np.asarray(load_mesh(asset.source, scale).triangles, dtype=float)
    except MeshError as error:
        raise SimMeshError(f"cannot simulate: {error}",
                           ref.where.span if ref.where else None) from None
    if np.prod(scale) < 0:  # a mirror turns the surface inside out: restore the winding
        triangles = triangles[:, ::-1, :]
    return triangles


def write_stl(path: str, triangles: np.ndarray) -> None:
    """Write (n, 3, 3) triangles (m) as a binary STL file with face normals."""
    triangles = np.asarray(triangles, dtype=np.float32).reshape(-1, 3, 3)
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.divide(normals, lengths, out=np.zeros_like(normals), where=lengths > 0)
    record = np.dtype([("normal", "<f4", 3), ("vertices", "<f4", (3, 3)), ("attr", "<u2")])
    data = np.zeros(len(triangles), dtype=record)
    data["normal"], data["vertices"] = normals, triangles
    with open(path, "wb") as handle:
        handle.write(b"robotdesc scratch mesh for DART".ljust(80, b" "))
        handle.write(np.uint32(len(triangles)).tobytes())
        handle.write(data.tobytes())


__all__ = ["DartUrdf", "dart_urdf", "write_stl"]
