"""Pure helpers over the kinematic tree of a `Robot`: parents, children, fixed-joint groups,
masses, adjacency. No Pinocchio needed."""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable

from robotdesc.model.elements import Joint, Link, Robot

#: Joint types with one degree of freedom read from a `<limit>`.
LIMITED_TYPES = frozenset({"revolute", "prismatic"})
#: Joint types that move (everything but fixed).
MOVING_TYPES = frozenset({"revolute", "continuous", "prismatic", "planar", "floating"})


def link_mass(link: Link | None) -> float:
    """The link's `<mass>` in kg (0 when it has no inertial or an unreadable mass)."""
    if link is None or link.inertial is None or link.inertial.mass is None:
        return 0.0
    return float(link.inertial.mass)


def children_of(robot: Robot) -> dict[str, list[Joint]]:
    """Link name -> the joints whose parent it is, in document order."""
    children: dict[str, list[Joint]] = defaultdict(list)
    for joint in robot.joints:
        children[joint.parent].append(joint)
    return children


def parent_joint_of(robot: Robot) -> dict[str, Joint]:
    """Link name -> the joint whose child it is (the first, when a link has several)."""
    parents: dict[str, Joint] = {}
    for joint in robot.joints:
        parents.setdefault(joint.child, joint)
    return parents


def fixed_group(robot: Robot, link: str) -> list[str]:
    """`link` and every link below it reached through fixed joints only (cycle-safe)."""
    children = children_of(robot)
    group, todo, seen = [], [link], {link}
    while todo:
        name = todo.pop()
        group.append(name)
        for joint in children.get(name, ()):
            if joint.type == "fixed" and joint.child not in seen:
                seen.add(joint.child)
                todo.append(joint.child)
    return group


def body_of(robot: Robot) -> dict[str, str]:
    """Link name -> the link that heads its rigid body (fixed joints merge links, as
    Pinocchio, Gazebo and MuJoCo importers do)."""
    parents = parent_joint_of(robot)
    head: dict[str, str] = {}
    for link in robot.links:
        name, seen = link.name, {link.name}
        while name in parents and parents[name].type == "fixed" and parents[name].parent not in seen:
            name = parents[name].parent
            seen.add(name)
        head[link.name] = name
    return head


def body_masses(robot: Robot) -> dict[str, float]:
    """Head link name -> total mass (kg) of the rigid body it heads."""
    masses: dict[str, float] = defaultdict(float)
    for link_name, head in body_of(robot).items():
        masses[head] += link_mass(robot.link(link_name))
    return dict(masses)


def has_collision(link: Link | None) -> bool:
    """True when the link has at least one `<collision>` with a geometry."""
    return link is not None and any(c.geometry is not None for c in link.collisions)


def adjacent_pairs(robot: Robot, with_geometry: Iterable[str],
                   collapse_fixed: bool = False) -> set[tuple[str, str]]:
    """Pairs of links with geometry that MoveIt calls adjacent (sorted name pairs).

    Two links are adjacent when a joint connects them, or when the path between them in the
    tree passes only through links without collision geometry (as MoveIt's Setup Assistant
    connects the neighbours of a geometry-less link). With `collapse_fixed`, links joined by
    fixed joints are first merged into one rigid body: links of one body are adjacent, and
    so are links of bodies that a joint (or a chain of bodies without geometry) connects.
    """
    if collapse_fixed:
        return _collapsed_adjacent_pairs(robot, set(with_geometry))
    solid = set(with_geometry)
    neighbours: dict[str, set[str]] = defaultdict(set)
    for joint in robot.joints:
        if joint.parent and joint.child and joint.parent != joint.child:
            neighbours[joint.parent].add(joint.child)
            neighbours[joint.child].add(joint.parent)
    pairs: set[tuple[str, str]] = set()
    for start in solid:
        todo, seen = list(neighbours[start]), {start}
        while todo:
            name = todo.pop()
            if name in seen:
                continue
            seen.add(name)
            if name in solid:
                pairs.add(tuple(sorted((start, name))))
            else:
                todo.extend(neighbours[name])
    return pairs


def _collapsed_adjacent_pairs(robot: Robot, solid: set[str]) -> set[tuple[str, str]]:
    head = body_of(robot)
    members: dict[str, list[str]] = defaultdict(list)
    for name in sorted(solid):
        members[head.get(name, name)].append(name)
    neighbours: dict[str, set[str]] = defaultdict(set)
    for joint in robot.joints:
        a, b = head.get(joint.parent, joint.parent), head.get(joint.child, joint.child)
        if a != b:
            neighbours[a].add(b)
            neighbours[b].add(a)
    pairs: set[tuple[str, str]] = set()
    for body, names in members.items():
        pairs.update(tuple(sorted((x, y))) for i, x in enumerate(names) for y in names[i + 1:])
        todo, seen = list(neighbours[body]), {body}
        while todo:
            other = todo.pop()
            if other in seen:
                continue
            seen.add(other)
            if members.get(other):
                pairs.update(tuple(sorted((x, y))) for x in names for y in members[other])
            else:
                todo.extend(neighbours[other])
    return pairs


def tree_problem(robot: Robot) -> tuple[str, str, object] | None:
    """Why the links and joints do not form one tree, or None when they do.

    Checked before handing a model to Pinocchio: urdfdom crashes the process on some cyclic
    graphs. Returns (message, element, provenance) of the first problem found.
    """
    if not robot.links:
        return "the robot has no links", f"robot:{robot.name}", robot.where
    seen: set[str] = set()
    for link in robot.links:
        if link.name in seen:
            return f"link '{link.name}' is defined twice", f"link:{link.name}", link.where
        seen.add(link.name)
    joints: set[str] = set()
    parents: dict[str, Joint] = {}
    for joint in robot.joints:
        element = f"joint:{joint.name}"
        if joint.name in joints:
            return f"joint '{joint.name}' is defined twice", element, joint.where
        joints.add(joint.name)
        for end in (joint.parent, joint.child):
            if end not in seen:
                return f"joint '{joint.name}' names link '{end}', which is not defined", \
                    element, joint.where
        if joint.parent == joint.child:
            return f"joint '{joint.name}' connects link '{joint.child}' to itself", element, \
                joint.where
        if joint.child in parents:
            return f"link '{joint.child}' has two parent joints", element, joint.where
        parents[joint.child] = joint
    roots = [link for link in robot.links if link.name not in parents]
    if len(roots) != 1:
        what = "no root link (a cycle)" if not roots else \
            "several root links: " + ", ".join(link.name for link in roots)
        return f"the links form {what}", f"robot:{robot.name}", robot.where
    return None
