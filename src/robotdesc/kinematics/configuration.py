"""Joint positions by name: the zero (neutral) and MoveIt-default configurations, limits, and
mimic joints following their drivers. Pure; positions in rad (revolute, continuous) or m
(prismatic)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from robotdesc.model.elements import Joint, Robot
from robotdesc.model.tree import SCALAR_TYPES, mimic_value


@dataclass(frozen=True)
class JointRange:
    """Where a one-variable joint may go.

    Attributes:
        name: the joint's name.
        lower: lowest position (rad or m); -pi for continuous joints.
        upper: highest position (rad or m); pi for continuous joints.
        bounded: True when the limits come from a `<limit>` (not a continuous joint).
    """

    name: str
    lower: float
    upper: float
    bounded: bool


def joint_range(joint: Joint) -> JointRange | None:
    """The range of a revolute, prismatic or continuous joint; None when unknown or unusable."""
    if joint.type == "continuous":
        return JointRange(joint.name, -math.pi, math.pi, False)
    if joint.type not in ("revolute", "prismatic") or joint.limit is None:
        return None
    lower, upper = joint.limit.lower, joint.limit.upper
    lower = 0.0 if lower is None else lower
    upper = 0.0 if upper is None else upper
    if not (math.isfinite(lower) and math.isfinite(upper)) or lower > upper:
        return None
    return JointRange(joint.name, lower, upper, True)


def default_position(joint: Joint) -> float:
    """MoveIt's default position: 0 when inside the limits, else the middle of the range."""
    found = joint_range(joint)
    if found is None or found.lower <= 0.0 <= found.upper:
        return 0.0
    return (found.lower + found.upper) / 2.0


def independent_joints(robot: Robot) -> list[Joint]:
    """The one-variable joints a user sets (not mimicking another joint), document order."""
    return [j for j in robot.joints if j.type in SCALAR_TYPES and not _mimics(robot, j)]


def _mimics(robot: Robot, joint: Joint) -> bool:
    return joint.mimic is not None and robot.joint(joint.mimic.joint) is not None


def follow_mimics(robot: Robot, positions: Mapping[str, float]) -> dict[str, float]:
    """Complete `positions` with every mimic joint: q = multiplier * q_driver + offset.

    Chains of mimic joints are followed; a mimic joint in a cycle gets 0. A value given for a
    mimic joint in `positions` is replaced by the one its driver implies.
    """
    mimicking = {j.name: j for j in robot.joints if j.type in SCALAR_TYPES and _mimics(robot, j)}
    result = {name: q for name, q in positions.items() if name not in mimicking}

    def value(name: str, visiting: frozenset[str]) -> float:
        if name in result:
            return result[name]
        joint = mimicking.get(name)
        if joint is None or joint.mimic is None or name in visiting:
            return 0.0
        result[name] = mimic_value(joint, value(joint.mimic.joint, visiting | {name}))
        return result[name]

    for name in mimicking:
        value(name, frozenset())
    return result


def zero_configuration(robot: Robot) -> dict[str, float]:
    """Every independent joint at 0, mimic joints following (Pinocchio's neutral)."""
    return follow_mimics(robot, {j.name: 0.0 for j in independent_joints(robot)})


def default_configuration(robot: Robot) -> dict[str, float]:
    """Every independent joint at MoveIt's default position, mimic joints following."""
    return follow_mimics(robot, {j.name: default_position(j) for j in independent_joints(robot)})
