"""Forward kinematics over the model: the world pose of every link at a configuration.

A small, dependency-free implementation (numpy only) for display: each joint moves its child
by `origin` then by its motion about (revolute, continuous) or along (prismatic) its unit
axis; fixed, floating and planar joints are drawn at their origin. Mimic joints follow
`multiplier * q[joint] + offset`. Units: metres and radians; transforms are 4x4 homogeneous
matrices mapping child-frame coordinates to world coordinates (the root links sit at the
world origin).
"""

from __future__ import annotations

import logging
import math
from collections import deque
from collections.abc import Mapping

import numpy as np

from robotdesc.errors import UsageError
from robotdesc.model.elements import Joint, Robot
from robotdesc.spatial import pose_matrix

log = logging.getLogger(__name__)

#: Joint types that take a value (rad or m).
MOVING_TYPES = frozenset({"revolute", "continuous", "prismatic"})
DEFAULT_AXIS = (1.0, 0.0, 0.0)


def axis_rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """The 3x3 rotation by `angle` (rad) about the unit vector `axis` (Rodrigues)."""
    x, y, z = axis
    c, s = math.cos(angle), math.sin(angle)
    t = 1.0 - c
    return np.array([[t * x * x + c, t * x * y - s * z, t * x * z + s * y],
                     [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
                     [t * x * z - s * y, t * y * z + s * x, t * z * z + c]])


def joint_motion(joint: Joint, value: float) -> np.ndarray:
    """The 4x4 motion of a joint at `value` (rad or m), applied after its origin."""
    motion = np.identity(4)
    if joint.type not in MOVING_TYPES or value == 0.0:
        return motion
    axis = np.asarray(joint.axis or DEFAULT_AXIS, dtype=float)
    norm = float(np.linalg.norm(axis))
    if not math.isfinite(norm) or norm == 0.0:
        return motion  # a zero axis is a lint finding; draw the joint unmoved
    axis = axis / norm
    if joint.type == "prismatic":
        motion[:3, 3] = axis * value
    else:
        motion[:3, :3] = axis_rotation(axis, value)
    return motion


def default_value(joint: Joint) -> float:
    """0, moved into the joint's limits when 0 lies outside them (as joint_state_publisher)."""
    if joint.type == "continuous" or joint.limit is None:
        return 0.0
    lower, upper = joint.limit.lower, joint.limit.upper
    if lower is not None and upper is not None and lower > upper:
        return 0.0
    if lower is not None and lower > 0.0:
        return lower
    if upper is not None and upper < 0.0:
        return upper
    return 0.0


def configuration(robot: Robot, values: Mapping[str, float] | None = None) -> dict[str, float]:
    """Every moving joint's value: given ones, defaults for the rest, mimic joints followed.

    Args:
        robot: the model.
        values: joint name -> value (rad or m) for independent moving joints.

    Returns:
        Joint name -> value for every revolute, continuous and prismatic joint.

    Raises:
        UsageError: a name is not a moving joint, or names a mimic joint.
    """
    joints = {j.name: j for j in robot.joints}
    given = dict(values or {})
    for name, value in given.items():
        joint = joints.get(name)
        if joint is None or joint.type not in MOVING_TYPES:
            moving = sorted((n for n, j in joints.items()
                             if j.type in MOVING_TYPES and j.mimic is None),
                            key=lambda n: (joints[n].type == "continuous", n))
            kind = "not a joint" if joint is None else f"a {joint.type} joint"
            raise UsageError(f"configuration: '{name}' is {kind}; moving joints: "
                             + (", ".join(moving[:12]) + (" ..." if len(moving) > 12 else "")
                                if moving else "none"))
        if joint.mimic is not None:
            raise UsageError(f"configuration: '{name}' mimics '{joint.mimic.joint}'; "
                             f"set '{joint.mimic.joint}' instead")
        if not math.isfinite(float(value)):
            raise UsageError(f"configuration: '{name}' must be a finite number, got {value}")
    resolved: dict[str, float] = {}

    def value_of(name: str, chain: tuple[str, ...]) -> float:
        if name in resolved:
            return resolved[name]
        joint = joints[name]
        mimic = joint.mimic
        if mimic is not None and mimic.joint in joints and mimic.joint not in chain \
                and joints[mimic.joint].type in MOVING_TYPES:
            leader = value_of(mimic.joint, chain + (name,))
            value = (mimic.multiplier if mimic.multiplier is not None else 1.0) * leader \
                + (mimic.offset if mimic.offset is not None else 0.0)
        else:
            value = float(given.get(name, default_value(joint)))
        resolved[name] = value
        return value

    for name, joint in joints.items():
        if joint.type in MOVING_TYPES:
            value_of(name, ())
    return resolved


def link_transforms(robot: Robot, values: Mapping[str, float] | None = None
                    ) -> dict[str, np.ndarray]:
    """World transform (4x4) of every link at a configuration.

    Root links (no parent joint) sit at the identity. A link that no root reaches (in a
    kinematic loop) is placed at the identity too, and logged.

    Args:
        robot: the model.
        values: joint name -> value (rad or m); see `configuration`.
    """
    return poses_at(robot, configuration(robot, values))


def poses_at(robot: Robot, q: Mapping[str, float]) -> dict[str, np.ndarray]:
    """World transform (4x4) of every link for a complete configuration (as returned by
    `configuration`: mimic joints already resolved; missing joints taken as 0)."""
    children: dict[str, list[Joint]] = {}
    has_parent = set()
    for joint in robot.joints:
        children.setdefault(joint.parent, []).append(joint)
        has_parent.add(joint.child)
    poses: dict[str, np.ndarray] = {}
    queue: deque[str] = deque()
    for link in robot.links:
        if link.name not in has_parent:
            poses[link.name] = np.identity(4)
            queue.append(link.name)
    while queue:
        parent = queue.popleft()
        for joint in children.get(parent, ()):
            if joint.child in poses:
                continue
            local = pose_matrix(joint.origin) @ joint_motion(joint, q.get(joint.name, 0.0))
            poses[joint.child] = poses[parent] @ local
            queue.append(joint.child)
    for link in robot.links:
        if link.name not in poses:
            log.info("link '%s' is not reached from a root link; drawn at the origin", link.name)
            poses[link.name] = np.identity(4)
    return poses


def parse_assignments(items: list[str] | tuple[str, ...]) -> dict[str, float]:
    """`name=value` strings (from `--q`) to a dict; radians or metres.

    Raises:
        UsageError: an item is not `name=number`.
    """
    values: dict[str, float] = {}
    for item in items:
        name, sep, text = item.partition("=")
        try:
            if not sep or not name.strip():
                raise ValueError
            values[name.strip()] = float(text)
        except ValueError:
            raise UsageError(f"--q '{item}': expected JOINT=VALUE (radians or metres)") from None
    return values
