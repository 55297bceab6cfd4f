"""Facts about a robot for `robotdesc info`: counts, degrees of freedom, mass, centre of mass
and bounding box (Pinocchio for the kinematics). Lengths in m, masses in kg."""

from __future__ import annotations

from collections import Counter
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from robotdesc.errors import UsageError
from robotdesc.kinematics.build import KinematicModel, build_model
from robotdesc.kinematics.configuration import follow_mimics, independent_joints
from robotdesc.kinematics.geometry import CollisionShape, collision_shapes
from robotdesc.kinematics.urdf_text import MeshPath
from robotdesc.model.elements import Robot

Vec3 = tuple[float, float, float]


@dataclass(frozen=True)
class MimicInfo:
    """A mimic joint: q = multiplier * q_driver + offset."""

    joint: str
    driver: str
    multiplier: float
    offset: float


@dataclass(frozen=True)
class RobotInfo:
    """What `robotdesc info` prints.

    Attributes:
        name: the robot's name.
        links: number of links.
        joints_by_type: joint type -> count.
        dof: degrees of freedom a user sets (Pinocchio's nv minus mimic joints).
        mimic: the mimic joints.
        total_mass: sum of link masses (kg).
        com_zero: centre of mass in the root frame at the zero configuration (m).
        com_at: centre of mass at `configuration` (m), or None when no configuration was given.
        configuration: the joint positions asked for (rad or m), mimic joints completed.
        bounds: (lower, upper) corner of the collision geometry in the root frame at the zero
            configuration (m), or None when the robot has no readable collision geometry.
        left_out: the `<collision>` elements the bounding box leaves out, with the reason
            (a mesh that does not resolve or cannot be read).
    """

    name: str
    links: int
    joints_by_type: tuple[tuple[str, int], ...]
    dof: int
    mimic: tuple[MimicInfo, ...]
    total_mass: float
    com_zero: Vec3
    com_at: Vec3 | None = None
    configuration: tuple[tuple[str, float], ...] = ()
    bounds: tuple[Vec3, Vec3] | None = None
    left_out: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, object]:
        """A JSON-ready dict (lists for tuples)."""
        return {"robot": self.name, "links": self.links,
                "joints_by_type": dict(self.joints_by_type), "dof": self.dof,
                "mimic": [vars(m) for m in self.mimic], "total_mass": self.total_mass,
                "com_zero": list(self.com_zero),
                "com_at": list(self.com_at) if self.com_at is not None else None,
                "configuration": dict(self.configuration),
                "bounds": [list(self.bounds[0]), list(self.bounds[1])] if self.bounds else None,
                "left_out": list(self.left_out)}


def robot_info(robot: Robot, mesh_path: MeshPath = lambda mesh: None,
               positions: Mapping[str, float] | None = None) -> RobotInfo:
    """Compute the facts of `robot`.

    Args:
        robot: the parsed robot.
        mesh_path: resolves `<mesh>` references (for the bounding box).
        positions: joint positions (rad or m) for `com_at`; names must be independent joints.

    Raises:
        UsageError: `positions` names a joint that is not an independent joint.
        KinematicsUnavailable, KinematicBuildError: see `build_model`.
    """
    settable = {joint.name for joint in independent_joints(robot)}
    unknown = sorted(set(positions or {}) - settable)
    if unknown:
        raise UsageError(f"--q: '{unknown[0]}' is not a joint you can set (choose from: "
                         f"{', '.join(sorted(settable)) or 'none'})")
    kinematics = build_model(robot, mesh_path)
    mimic = tuple(MimicInfo(j.name, j.mimic.joint, 1.0 if j.mimic.multiplier is None
                            else j.mimic.multiplier, 0.0 if j.mimic.offset is None
                            else j.mimic.offset)
                  for j in robot.joints if j.mimic is not None and j.name not in settable
                  and robot.joint(j.mimic.joint) is not None)
    zero = follow_mimics(robot, {name: 0.0 for name in settable})
    com_zero = _com(kinematics, zero)
    chosen = follow_mimics(robot, {**zero, **dict(positions)}) if positions else None
    shapes, problems = collision_shapes(robot, mesh_path)
    return RobotInfo(
        name=robot.name, links=len(robot.links),
        joints_by_type=tuple(sorted(Counter(j.type for j in robot.joints).items())),
        dof=int(kinematics.model.nv) - len(mimic),
        mimic=mimic, total_mass=float(sum(i.mass for i in kinematics.model.inertias)),
        com_zero=com_zero, com_at=_com(kinematics, chosen) if chosen else None,
        configuration=tuple(sorted(chosen.items())) if chosen else (),
        bounds=_bounds(kinematics, shapes, zero),
        left_out=tuple(f"link '{p.link}': {p.message}" for p in problems))


def _com(kinematics: KinematicModel, positions: Mapping[str, float]) -> Vec3:
    import pinocchio as pin

    model = kinematics.model
    data = model.createData()
    pin.forwardKinematics(model, data, kinematics.configuration(dict(positions)))
    total, moment = 0.0, np.zeros(3)
    for index in range(model.njoints):  # joint 0 holds the root link: pin.centerOfMass skips it
        inertia = model.inertias[index]
        total += inertia.mass
        moment += inertia.mass * np.asarray(data.oMi[index].act(inertia.lever))
    com = moment / total if total > 0 else np.zeros(3)
    x, y, z = (float(c) for c in com)
    return (x, y, z)


def _bounds(kinematics: KinematicModel, shapes: list[CollisionShape],
            positions: Mapping[str, float]) -> tuple[Vec3, Vec3] | None:
    import pinocchio as pin

    if not shapes:
        return None
    model = kinematics.model
    data = model.createData()
    pin.framesForwardKinematics(model, data, kinematics.configuration(dict(positions)))
    points = []
    for shape in shapes:
        frame = data.oMf[model.getFrameId(shape.link, pin.BODY)]
        local = shape.link_points()
        points.append(local @ np.asarray(frame.rotation).T + np.asarray(frame.translation))
    stacked = np.vstack(points)
    low_x, low_y, low_z = map(float, stacked.min(axis=0))
    high_x, high_y, high_z = map(float, stacked.max(axis=0))
    return (low_x, low_y, low_z), (high_x, high_y, high_z)
