"""Write the parts of a `Robot` that Pinocchio reads back as URDF text.

Links (inertial, collision geometry) and joints (origin, axis, limit, dynamics, mimic) are
written from the strict model, so Pinocchio sees exactly what robotdesc parsed. Mesh
filenames are replaced by the files robotdesc's own package resolver found (absolute paths),
so no ROS lookup happens; a mesh that does not resolve is left out (other rules report it).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from robotdesc.model.elements import (
    Box,
    Capsule,
    Collision,
    Cylinder,
    Geometry,
    Inertial,
    Joint,
    Link,
    MeshRef,
    Pose,
    Robot,
    Sphere,
)
from robotdesc.xml_text import quote_attribute

#: Resolves a mesh reference to an absolute file path, or None.
MeshPath = Callable[[MeshRef], "str | None"]


def _numbers(values: Iterable[float]) -> str:
    return " ".join(repr(float(v)) for v in values)


def _origin(pose: Pose) -> str:
    return f'<origin xyz="{_numbers(pose.xyz)}" rpy="{_numbers(pose.rpy)}"/>'


def _geometry(geometry: Geometry, mesh_path: MeshPath) -> str | None:
    if isinstance(geometry, Box):
        return f'<box size="{_numbers(geometry.size)}"/>'
    if isinstance(geometry, Cylinder):
        return f'<cylinder radius="{geometry.radius!r}" length="{geometry.length!r}"/>'
    if isinstance(geometry, Sphere):
        return f'<sphere radius="{geometry.radius!r}"/>'
    if isinstance(geometry, Capsule):
        return f'<capsule radius="{geometry.radius!r}" length="{geometry.length!r}"/>'
    if isinstance(geometry, MeshRef):
        path = mesh_path(geometry)
        if path is None:
            return None
        return f'<mesh filename={quote_attribute(path)} scale="{_numbers(geometry.scale)}"/>'
    return None


def _inertial(inertial: Inertial) -> list[str]:
    lines = ["    <inertial>", "      " + _origin(inertial.origin)]
    if inertial.mass is not None:
        lines.append(f'      <mass value="{inertial.mass!r}"/>')
    if inertial.inertia is not None:
        i = inertial.inertia
        lines.append(f'      <inertia ixx="{i.ixx!r}" ixy="{i.ixy!r}" ixz="{i.ixz!r}" '
                     f'iyy="{i.iyy!r}" iyz="{i.iyz!r}" izz="{i.izz!r}"/>')
    lines.append("    </inertial>")
    return lines


def _collision(collision: Collision, mesh_path: MeshPath) -> list[str]:
    shape = _geometry(collision.geometry, mesh_path) if collision.geometry else None
    if shape is None:
        return []
    name = f" name={quote_attribute(collision.name)}" if collision.name else ""
    return [f"    <collision{name}>", "      " + _origin(collision.origin),
            f"      <geometry>{shape}</geometry>", "    </collision>"]


def _link(link: Link, mesh_path: MeshPath) -> list[str]:
    lines = [f"  <link name={quote_attribute(link.name)}>"]
    if link.inertial is not None:
        lines += _inertial(link.inertial)
    for collision in link.collisions:
        lines += _collision(collision, mesh_path)
    return lines + ["  </link>"]


def _joint(joint: Joint) -> list[str]:
    lines = [f"  <joint name={quote_attribute(joint.name)} type={quote_attribute(joint.type)}>",
             f"    <parent link={quote_attribute(joint.parent)}/>",
             f"    <child link={quote_attribute(joint.child)}/>", "    " + _origin(joint.origin)]
    if joint.axis is not None:
        lines.append(f'    <axis xyz="{_numbers(joint.axis)}"/>')
    if joint.limit is not None:
        limit = joint.limit
        parts = [f'{key}="{value!r}"' for key, value in (
            ("lower", limit.lower), ("upper", limit.upper), ("effort", limit.effort),
            ("velocity", limit.velocity)) if value is not None]
        lines.append(f"    <limit {' '.join(parts)}/>")
    if joint.dynamics is not None:
        parts = [f'{key}="{value!r}"' for key, value in (
            ("damping", joint.dynamics.damping), ("friction", joint.dynamics.friction))
            if value is not None]
        lines.append(f"    <dynamics {' '.join(parts)}/>")
    if joint.mimic is not None and joint.mimic.joint:
        mimic = joint.mimic
        multiplier = 1.0 if mimic.multiplier is None else mimic.multiplier
        offset = 0.0 if mimic.offset is None else mimic.offset
        lines.append(f'    <mimic joint={quote_attribute(mimic.joint)} multiplier="{multiplier!r}" '
                     f'offset="{offset!r}"/>')
    return lines + ["  </joint>"]


def pinocchio_urdf(robot: Robot, mesh_path: MeshPath = lambda mesh: None) -> str:
    """The robot as URDF text for Pinocchio (links, joints, collision geometry).

    Args:
        robot: the parsed robot.
        mesh_path: resolves a `<mesh>` to an absolute file (default: meshes are left out).
    """
    lines = ['<?xml version="1.0"?>', f"<robot name={quote_attribute(robot.name or 'robot')}>"]
    for link in robot.links:
        lines += _link(link, mesh_path)
    for joint in robot.joints:
        lines += _joint(joint)
    return "\n".join(lines + ["</robot>", ""])
