"""Which link pairs can ever meet: bounding spheres swept over the joint ranges (pure numpy).

Each link's collision geometry is bounded by a sphere in its own frame. Walking up the tree,
the sphere is swept over every joint between the link and an ancestor: a revolute or
continuous joint turns it about the joint's axis (the sphere bounding the arc its centre
describes, grown by its radius), a prismatic joint slides it along the axis, a fixed joint
only moves it. Two links whose swept spheres, expressed in the frame of their deepest common
ancestor link, stay apart can never collide in any configuration the sampler can draw: their
pair is Never without sampling. Mimic joints get the range their drivers imply. Planar and
floating joints, and joints with a zero axis, make the reach unbounded (nothing is pruned
through them). Units: metres and radians.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from robotdesc.kinematics.configuration import follow_mimics, independent_joints, joint_range
from robotdesc.kinematics.geometry import CollisionShape
from robotdesc.model.elements import Joint, Robot
from robotdesc.spatial import pose_matrix

#: Spheres closer than this (m) count as meeting: a margin for rounding.
MARGIN = 1e-6
#: How far a spinning shape may sit off its joint's axis (m), or tilt from it (rad, as the
#: sine), and still count as symmetric about it (URDFs write pi/2 as 1.5707963).
SPIN_TOLERANCE = 1e-6


@dataclass(frozen=True)
class Sphere:
    """A bounding sphere: centre (x, y, z) and radius, m (radius inf: unbounded)."""

    centre: tuple[float, float, float]
    radius: float


def bounding_sphere(points: np.ndarray) -> Sphere:
    """A sphere around `points` ((k, 3), m): the box centre and the farthest point."""
    low, high = points.min(axis=0), points.max(axis=0)
    centre = (low + high) / 2.0
    radius = float(np.linalg.norm(points - centre, axis=1).max())
    x, y, z = (float(v) for v in centre)
    return Sphere((x, y, z), radius)


def link_spheres(shapes: Iterable[CollisionShape]) -> dict[str, Sphere]:
    """Link name -> the sphere bounding all its collision shapes, in the link frame (m)."""
    points: dict[str, list[np.ndarray]] = {}
    for shape in shapes:
        points.setdefault(shape.link, []).append(shape.link_points())
    return {link: bounding_sphere(np.vstack(parts)) for link, parts in points.items()}


def shape_spheres(shapes: Iterable[CollisionShape]) -> tuple[Sphere, ...]:
    """Per shape, the sphere bounding it in its link's frame (m)."""
    return tuple(bounding_sphere(shape.link_points()) for shape in shapes)


def joint_ranges(robot: Robot) -> dict[str, tuple[float, float]]:
    """Joint name -> (lowest, highest) position the sampler can give it (rad or m).

    Independent joints: their limits ([-pi, pi] when continuous, 0 when unusable); mimic
    joints: the image of their driver's range (affine, so its two ends bound it).
    """
    low, high = {}, {}
    for joint in independent_joints(robot):
        found = joint_range(joint)
        low[joint.name], high[joint.name] = (found.lower, found.upper) if found else (0.0, 0.0)
    at_low, at_high = follow_mimics(robot, low), follow_mimics(robot, high)
    return {name: (min(at_low[name], at_high[name]), max(at_low[name], at_high[name]))
            for name in at_low}


def _rotate(axis: np.ndarray, angle: float, vector: np.ndarray) -> np.ndarray:
    """`vector` turned by `angle` (rad) about the unit `axis` (Rodrigues)."""
    c, s = math.cos(angle), math.sin(angle)
    return vector * c + np.cross(axis, vector) * s + axis * float(axis @ vector) * (1.0 - c)


def sweep(joint: Joint, sphere: Sphere, span: tuple[float, float] | None) -> Sphere:
    """The sphere in the parent link's frame bounding `sphere` (given in the child's frame)
    over every position of `joint` within `span` (rad or m; None: the joint does not move)."""
    if not math.isfinite(sphere.radius):
        return sphere
    centre, radius = np.asarray(sphere.centre, dtype=float), sphere.radius
    if joint.type in ("revolute", "continuous", "prismatic") and span is not None \
            and span[1] > span[0]:
        axis = np.asarray(joint.axis or (1.0, 0.0, 0.0), dtype=float)
        norm = float(np.linalg.norm(axis))
        if not math.isfinite(norm) or norm == 0.0:
            return Sphere(sphere.centre, math.inf)
        axis = axis / norm
        lower, upper = span
        if joint.type == "prismatic":
            centre = centre + axis * (lower + upper) / 2.0
            radius += (upper - lower) / 2.0
        else:
            along = axis * float(axis @ centre)
            arm = centre - along
            reach = float(np.linalg.norm(arm))
            half = (upper - lower) / 2.0
            if half <= math.pi / 2.0:
                middle = _rotate(axis, (lower + upper) / 2.0, arm)
                centre = along + math.cos(half) * middle
                radius += reach * math.sin(half)
            else:
                centre = along
                radius += reach
    elif joint.type in ("planar", "floating"):
        return Sphere(sphere.centre, math.inf)
    elif span is not None and joint.type in ("revolute", "continuous", "prismatic"):
        centre = _move(joint, span[0], centre)
    origin = pose_matrix(joint.origin)
    placed = origin[:3, :3] @ centre + origin[:3, 3]
    x, y, z = (float(v) for v in placed)
    return Sphere((x, y, z), radius)


def _move(joint: Joint, value: float, centre: np.ndarray) -> np.ndarray:
    """`centre` moved by the joint at one position (`value`, rad or m)."""
    if value == 0.0:
        return centre
    axis = np.asarray(joint.axis or (1.0, 0.0, 0.0), dtype=float)
    norm = float(np.linalg.norm(axis))
    if not math.isfinite(norm) or norm == 0.0:
        return centre
    axis = axis / norm
    if joint.type == "prismatic":
        return centre + axis * value
    return _rotate(axis, value, centre)


def spin_only(robot: Robot, joint: Joint, shapes: Iterable[CollisionShape]) -> bool:
    """True when `joint` only turns geometry that is symmetric about its axis: a revolute or
    continuous joint whose child hangs nothing but fixed links, every shape of which is a
    sphere centred on the axis, or a cylinder or capsule lying along it (a wheel)."""
    if joint.type not in ("revolute", "continuous"):
        return False
    axis = np.asarray(joint.axis or (1.0, 0.0, 0.0), dtype=float)
    norm = float(np.linalg.norm(axis))
    if not math.isfinite(norm) or norm == 0.0:
        return False
    axis = axis / norm
    by_link: dict[str, list[CollisionShape]] = {}
    for shape in shapes:
        by_link.setdefault(shape.link, []).append(shape)
    below: dict[str, list[Joint]] = {}
    for other in robot.joints:
        below.setdefault(other.parent, []).append(other)
    todo, seen = [(joint.child, np.identity(4))], {joint.child}
    while todo:
        link, placement = todo.pop()
        for shape in by_link.get(link, ()):
            frame = placement @ shape.placement
            centre = frame[:3, 3]
            if float(np.linalg.norm(centre - axis * float(axis @ centre))) > SPIN_TOLERANCE:
                return False
            if shape.kind in ("cylinder", "capsule"):
                if float(np.linalg.norm(np.cross(frame[:3, 2], axis))) > SPIN_TOLERANCE:
                    return False
            elif shape.kind != "sphere":
                return False
        for child in below.get(link, ()):
            if child.type != "fixed" or child.child in seen:
                return False
            seen.add(child.child)
            todo.append((child.child, placement @ pose_matrix(child.origin)))
    return True


@dataclass(frozen=True, eq=False)
class Reach:
    """Swept spheres of every link with geometry, relative to each of its ancestors.

    Attributes:
        ancestors: link name -> its ancestor links, root first, itself last.
        spheres: link name -> one sphere per entry of `ancestors` (in that ancestor's frame).
        moves: link name -> per entry of `ancestors`: does the link's geometry move relative
            to that ancestor (a joint between them takes more than one position and is not
            `spin_only`)?
    """

    ancestors: dict[str, tuple[str, ...]]
    spheres: dict[str, tuple[Sphere, ...]]
    moves: dict[str, tuple[bool, ...]]

    def _common(self, first: str, second: str) -> int:
        """1 + the index of the deepest common ancestor (0: none)."""
        one, two = self.ancestors.get(first, ()), self.ancestors.get(second, ())
        depth = 0
        while depth < min(len(one), len(two)) and one[depth] == two[depth]:
            depth += 1
        return depth

    def rigid(self, first: str, second: str) -> bool:
        """True when the two links' geometry keeps its relative placement in every sample
        (so the default configuration decides the pair)."""
        depth = self._common(first, second)
        return depth > 0 and not (self.moves[first][depth - 1] or self.moves[second][depth - 1])

    def can_meet(self, first: str, second: str) -> bool:
        """False when the two links can never touch (their swept spheres stay apart)."""
        if first not in self.ancestors or second not in self.ancestors:
            return True
        depth = self._common(first, second)
        if depth == 0:
            return True  # no common ancestor: not one tree
        a, b = self.spheres[first][depth - 1], self.spheres[second][depth - 1]
        if not (math.isfinite(a.radius) and math.isfinite(b.radius)):
            return True
        gap = math.dist(a.centre, b.centre) - a.radius - b.radius
        return gap <= MARGIN


def reach(robot: Robot, shapes: Iterable[CollisionShape]) -> Reach:
    """The swept spheres of every link that has collision shapes (see the module doc)."""
    parents: dict[str, Joint] = {}
    for joint in robot.joints:
        parents.setdefault(joint.child, joint)
    shapes = list(shapes)
    spans = joint_ranges(robot)
    still = {joint.name: _still(robot, joint, spans.get(joint.name), shapes)
             for joint in robot.joints}
    ancestors: dict[str, tuple[str, ...]] = {}
    spheres: dict[str, tuple[Sphere, ...]] = {}
    moves: dict[str, tuple[bool, ...]] = {}
    for link, sphere in link_spheres(shapes).items():
        chain, found, moving, seen = [link], [sphere], [False], {link}
        while chain[-1] in parents and parents[chain[-1]].parent not in seen:
            joint = parents[chain[-1]]
            found.append(sweep(joint, found[-1], spans.get(joint.name)))
            moving.append(moving[-1] or not still[joint.name])
            chain.append(joint.parent)
            seen.add(joint.parent)
        ancestors[link] = tuple(reversed(chain))
        spheres[link] = tuple(reversed(found))
        moves[link] = tuple(reversed(moving))
    return Reach(ancestors, spheres, moves)


def _still(robot: Robot, joint: Joint, span: tuple[float, float] | None,
           shapes: list[CollisionShape]) -> bool:
    """The joint never moves geometry: fixed, one position only, or `spin_only`."""
    if joint.type == "fixed":
        return True
    if joint.type in ("planar", "floating"):
        return False
    if span is None or span[1] <= span[0]:
        return True
    return spin_only(robot, joint, shapes)
