"""Random joint configurations within the limits, reproducible from a seed (pure numpy)."""

from __future__ import annotations

from typing import cast

import numpy as np

from robotdesc.kinematics.configuration import follow_mimics, independent_joints, joint_range
from robotdesc.model.elements import Robot


def sample_positions(robot: Robot, count: int, seed: int) -> tuple[list[str], np.ndarray]:
    """`count` configurations drawn uniformly within each joint's limits.

    Independent revolute and prismatic joints are drawn within `<limit lower upper>`,
    continuous joints within [-pi, pi]; mimic joints follow their drivers. Joints without
    usable limits stay at 0. The same robot, count and seed give the same array.

    Returns:
        The joint names (columns) and a (count, joints) array of positions (rad or m).
    """
    rng = np.random.default_rng(seed)
    drivers = independent_joints(robot)
    columns = []
    for joint in drivers:
        found = joint_range(joint)
        low, high = (found.lower, found.upper) if found else (0.0, 0.0)
        columns.append(rng.uniform(low, high, size=count))
    driven = np.column_stack(columns) if columns else np.zeros((count, 0))
    names = [j.name for j in drivers]
    complete = follow_mimics(robot, {name: 0.0 for name in names})
    followers = [name for name in complete if name not in names]
    if not followers:
        return names, driven
    # follow_mimics is affine per joint, so whole columns go through it at once (arrays in
    # place of its floats)
    columns_by_name = cast("dict[str, float]", {name: driven[:, k] for k, name in enumerate(names)})
    values = follow_mimics(robot, columns_by_name)
    rows = np.column_stack([np.broadcast_to(np.asarray(values[name], dtype=float), (count,))
                            for name in followers])
    return names + followers, np.hstack([driven, rows])
