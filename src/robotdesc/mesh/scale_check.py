"""Does a mesh look like it was exported in millimetres? Compare its size with the robot's.

The robot's size is the diagonal of the box spanned by its joint frames at the zero
configuration (m); a robot without joints has no size of its own and is judged by its other
meshes only.
"""

from __future__ import annotations

import statistics
from typing import Sequence

import numpy as np

from robotdesc.mesh.mass import rpy_matrix
from robotdesc.model.elements import Robot

#: A mesh is suspicious when it is this many times larger than the robot (or its peers).
TOO_LARGE_FACTOR = 20.0
#: ... and at least this large (m): small robots may carry a large base plate or a table.
MIN_SUSPICIOUS_SIZE = 2.0


def robot_size(robot: Robot) -> float:
    """Diagonal (m) of the bounding box of all joint frame origins at zero joint values."""
    children: dict[str, list] = {}
    for joint in robot.joints:
        children.setdefault(joint.parent, []).append(joint)
    child_names = {j.child for j in robot.joints}
    roots = [link.name for link in robot.links if link.name not in child_names]
    points = []
    stack = [(name, np.eye(3), np.zeros(3)) for name in roots]
    seen = set()
    while stack:
        name, rotation, position = stack.pop()
        if name in seen:
            continue
        seen.add(name)
        points.append(position)
        for joint in children.get(name, ()):
            offset = rotation @ np.asarray(joint.origin.xyz, dtype=float)
            stack.append((joint.child, rotation @ rpy_matrix(joint.origin.rpy),
                          position + offset))
    if len(points) < 2:
        return 0.0
    cloud = np.asarray(points)
    return float(np.linalg.norm(cloud.max(axis=0) - cloud.min(axis=0)))


def looks_like_millimetres(diagonal: float, size: float, others: Sequence[float]) -> bool:
    """Whether a mesh of bounding-box `diagonal` (m) is about 1000 times too large.

    Args:
        diagonal: the mesh's bounding-box diagonal after the URDF scale (m).
        size: the robot's size from its joints (m), 0 when unknown.
        others: the diagonals of the robot's other meshes (m).
    """
    if diagonal < MIN_SUSPICIOUS_SIZE:
        return False
    reference = size if size > 0 else (statistics.median(others) if others else 0.0)
    if reference <= 0:
        return False
    return diagonal > TOO_LARGE_FACTOR * reference and diagonal / 1000 < 5 * reference
