"""Forward kinematics for many configurations at once (numpy): where each link's bounding
sphere lies in every sample, for the broad phase of the self-collision matrix.

Each joint places its child by `origin` then by its motion about (revolute, continuous) or
along (prismatic) its unit axis, as Pinocchio's URDF reader does; fixed joints only place.
Units: metres and radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from robotdesc.model.elements import Robot
from robotdesc.spatial import pose_matrix


@dataclass(frozen=True, eq=False)
class Chain:
    """The tree in walking order, as plain arrays (picklable).

    Attributes:
        links: link names; index 0 is the root.
        parent: per link, the index of its parent link (-1 for the root).
        origin: per link, (4, 4) placement of its joint's frame in the parent frame (m).
        axis: per link, the unit joint axis (zeros when the joint does not move).
        prismatic: per link, True when its joint slides.
        column: per link, the column of its joint in the positions array (-1: none).
    """

    links: tuple[str, ...]
    parent: np.ndarray
    origin: np.ndarray
    axis: np.ndarray
    prismatic: np.ndarray
    column: np.ndarray


def chain(robot: Robot, columns: list[str]) -> Chain:
    """The walking order of `robot`'s tree; `columns` names the joints of the positions array."""
    column_of = {name: k for k, name in enumerate(columns)}
    below: dict[str, list] = {}
    has_parent = set()
    for joint in robot.joints:
        below.setdefault(joint.parent, []).append(joint)
        has_parent.add(joint.child)
    roots = [link.name for link in robot.links if link.name not in has_parent]
    links, parent, origin, axis, prismatic, column = [], [], [], [], [], []
    index: dict[str, int] = {}
    todo = [(root, None) for root in reversed(roots)]
    while todo:
        name, joint = todo.pop()
        if name in index:
            continue
        index[name] = len(links)
        links.append(name)
        if joint is None:
            parent.append(-1)
            origin.append(np.identity(4))
            axis.append(np.zeros(3))
            prismatic.append(False)
            column.append(-1)
        else:
            parent.append(index[joint.parent])
            origin.append(pose_matrix(joint.origin))
            vector = np.asarray(joint.axis or (1.0, 0.0, 0.0), dtype=float)
            norm = float(np.linalg.norm(vector))
            moving = joint.type in ("revolute", "continuous", "prismatic") \
                and joint.name in column_of and math.isfinite(norm) and norm > 0.0
            axis.append(vector / norm if moving else np.zeros(3))
            prismatic.append(joint.type == "prismatic")
            column.append(column_of[joint.name] if moving else -1)
        for child in reversed(below.get(name, [])):
            todo.append((child.child, child))
    return Chain(tuple(links), np.asarray(parent), np.asarray(origin), np.asarray(axis),
                 np.asarray(prismatic, dtype=bool), np.asarray(column))


def link_frames(tree: Chain, positions: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """World frames of every link of `tree` for every row of `positions`.

    Args:
        tree: from `chain`.
        positions: (n, columns) joint positions, rad or m.

    Returns:
        Rotations (n, links, 3, 3) and translations (n, links, 3), m.
    """
    count = len(positions)
    rotations = np.empty((count, len(tree.links), 3, 3))
    translations = np.empty((count, len(tree.links), 3))
    identity = np.identity(3)
    for k in range(len(tree.links)):
        origin, parent = tree.origin[k], tree.parent[k]
        if parent < 0:
            rotation = np.broadcast_to(origin[:3, :3], (count, 3, 3))
            translation = np.broadcast_to(origin[:3, 3], (count, 3))
        else:
            rotation = rotations[:, parent] @ origin[:3, :3]
            translation = rotations[:, parent] @ origin[:3, 3] + translations[:, parent]
        if tree.column[k] >= 0:
            value, a = positions[:, tree.column[k]], tree.axis[k]
            if tree.prismatic[k]:
                translation = translation + rotation @ a * value[:, None]
            else:
                c, s = np.cos(value)[:, None, None], np.sin(value)[:, None, None]
                cross = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
                motion = c * identity + s * cross + (1.0 - c) * np.outer(a, a)
                rotation = rotation @ motion
        rotations[:, k] = rotation
        translations[:, k] = translation
    return rotations, translations
