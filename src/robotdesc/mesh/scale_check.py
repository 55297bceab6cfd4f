"""Does a mesh look like it was exported in millimetres? Compare its size with the robot's.

The robot's size is the diagonal of the box spanned by its joint frames at the zero
configuration (m); a robot without joints has no size of its own and is judged by its other
meshes only. Plain Python (a few joints need no numpy).
"""

from __future__ import annotations

from collections.abc import Sequence

from robotdesc.model.elements import Robot
from robotdesc.model.tree import children_of, roots
from robotdesc.spatial import add, compose, norm, rotate, rpy_rotation, subtract

#: A mesh is suspicious when it is this many times larger than the robot (or its peers).
TOO_LARGE_FACTOR = 20.0
#: ... and at least this large (m): small robots may carry a large base plate or a table.
MIN_SUSPICIOUS_SIZE = 2.0


def robot_size(robot: Robot) -> float:
    """Diagonal (m) of the bounding box of all joint frame origins at zero joint values.

    Plain Python over `model.tree`'s parents and children, not its numpy forward kinematics:
    a warm lint (meshes from the cache) must not import numpy (tests/mesh/test_warm_imports).
    """
    children = children_of(robot)
    identity = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    points = []
    stack = [(link.name, identity, (0.0, 0.0, 0.0)) for link in roots(robot)]
    seen = set()
    while stack:
        name, rotation, position = stack.pop()
        if name in seen:
            continue
        seen.add(name)
        points.append(position)
        for joint in children.get(name, ()):
            offset = rotate(rotation, [float(v) for v in joint.origin.xyz])
            stack.append((joint.child, compose(rotation, rpy_rotation(joint.origin.rpy)),
                          add(position, offset)))
    if len(points) < 2:
        return 0.0
    low = tuple(min(p[i] for p in points) for i in range(3))
    high = tuple(max(p[i] for p in points) for i in range(3))
    return norm(subtract(high, low))


def looks_like_millimetres(diagonal: float, size: float, others: Sequence[float]) -> bool:
    """Whether a mesh of bounding-box `diagonal` (m) is about 1000 times too large.

    Args:
        diagonal: the mesh's bounding-box diagonal after the URDF scale (m).
        size: the robot's size from its joints (m), 0 when unknown.
        others: the diagonals of the robot's other meshes (m).
    """
    if diagonal < MIN_SUSPICIOUS_SIZE:
        return False
    reference = size if size > 0 else (_median(others) if others else 0.0)
    if reference <= 0:
        return False
    return diagonal > TOO_LARGE_FACTOR * reference and diagonal / 1000 < 5 * reference


def _median(values: Sequence[float]) -> float:
    """The median (the `statistics` module costs more to import than this whole check)."""
    ordered = sorted(values)
    middle = len(ordered) // 2
    return ordered[middle] if len(ordered) % 2 else (ordered[middle - 1] + ordered[middle]) / 2
