"""The kinematic tree of a `Robot`: parents, children, roots, cycles, fixed-joint groups,
mimic resolution and forward kinematics. The one implementation every layer uses (rules,
view, sim, kinematics, srdf).

The structural functions are plain Python (a lint must not import numpy); forward kinematics
(`joint_motion`, `poses_at`, `link_transforms`, and `joint_chain` / `link_frames` for many
configurations at once) imports numpy when called. Units: metres and
radians; poses are 4x4 homogeneous matrices mapping child-frame coordinates to world
coordinates, the root links at the world origin.

`robotdesc.model.elements` imports this module (a `Robot`'s repr draws the top of its tree
through `summary.py`), so the model's classes are imported here for type checking only.
"""

from __future__ import annotations

import logging
import math
from collections import defaultdict, deque
from collections.abc import Collection, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from robotdesc.errors import UsageError
from robotdesc.spatial import pose_matrix

if TYPE_CHECKING:  # elements imports this module at run time: types only here
    import numpy as np

    from robotdesc.model.elements import Joint, Link, Robot
    from robotdesc.source import Provenance

log = logging.getLogger(__name__)

#: Joint types with one degree of freedom read from a `<limit>`.
LIMITED_TYPES = frozenset({"revolute", "prismatic"})
#: Joint types that move (everything but fixed).
MOVING_TYPES = frozenset({"revolute", "continuous", "prismatic", "planar", "floating"})
#: Joint types with one position variable (rad or m): the ones a configuration sets.
SCALAR_TYPES = frozenset({"revolute", "continuous", "prismatic"})
#: The axis of a joint without `<axis>` (URDF's default).
DEFAULT_AXIS = (1.0, 0.0, 0.0)


# --- parents, children, roots -------------------------------------------------------------

def children_of(robot: Robot) -> dict[str, list[Joint]]:
    """Link name -> the joints whose parent it is, in document order (a defaultdict)."""
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


def roots(robot: Robot) -> list[Link]:
    """The links that are no joint's child, in document order (several, or none in a cycle,
    when the links do not form one tree)."""
    children = {joint.child for joint in robot.joints}
    return [link for link in robot.links if link.name not in children]


def connected_roots(robot: Robot) -> list[Link]:
    """The roots (see `roots`) that are some joint's parent: the heads of trees, leaving out
    links that no joint mentions."""
    parents = {joint.parent for joint in robot.joints}
    return [link for link in roots(robot) if link.name in parents]


def mentioned_links(robot: Robot) -> set[str]:
    """The names of the links some joint names as its parent or child."""
    return {joint.parent for joint in robot.joints} | {joint.child for joint in robot.joints}


def subtree(robot: Robot, link: str) -> list[str]:
    """`link` and every link below it, breadth first in document order (cycle-safe)."""
    children = children_of(robot)
    found, todo, seen = [], deque([link]), {link}
    while todo:
        name = todo.popleft()
        found.append(name)
        for joint in children.get(name, ()):
            if joint.child not in seen:
                seen.add(joint.child)
                todo.append(joint.child)
    return found


# --- fixed-joint groups -------------------------------------------------------------------

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


def body_of(robot: Robot, keep: Collection[str] = ()) -> dict[str, str]:
    """Link name -> the link that heads its rigid body (fixed joints merge links, as
    Pinocchio, Gazebo and MuJoCo importers do); fixed joints named in `keep` do not merge."""
    parents = parent_joint_of(robot)
    head: dict[str, str] = {}
    for link in robot.links:
        name, seen = link.name, {link.name}
        while name in parents and parents[name].type == "fixed" \
                and parents[name].name not in keep and parents[name].parent not in seen:
            name = parents[name].parent
            seen.add(name)
        head[link.name] = name
    return head


def link_mass(link: Link | None) -> float:
    """The link's `<mass>` in kg (0 when it has no inertial or an unreadable mass)."""
    if link is None or link.inertial is None or link.inertial.mass is None:
        return 0.0
    return float(link.inertial.mass)


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
                pairs.add(_pair(start, name))
            else:
                todo.extend(neighbours[name])
    return pairs


def _pair(a: str, b: str) -> tuple[str, str]:
    """The two names in sorted order."""
    return (a, b) if a <= b else (b, a)


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
        pairs.update(_pair(x, y) for i, x in enumerate(names) for y in names[i + 1:])
        todo, seen = list(neighbours[body]), {body}
        while todo:
            other = todo.pop()
            if other in seen:
                continue
            seen.add(other)
            if members.get(other):
                pairs.update(_pair(x, y) for x in names for y in members[other])
            else:
                todo.extend(neighbours[other])
    return pairs


# --- cycles and tree defects --------------------------------------------------------------

def cycles(robot: Robot) -> list[tuple[Joint, list[str]]]:
    """The kinematic loops: for each, the first joint (document order) inside it and the
    sorted names of its links. Joints naming a missing link are left out; a joint from a
    link to itself is no loop here (see `self_joints`)."""
    links = {link.name for link in robot.links}
    edges = [joint for joint in robot.joints if joint.parent in links and joint.child in links]
    components = _strongly_connected(edges)
    found = []
    for joint in _first_joint_per_cycle(edges, components):
        members = sorted(name for name, comp in components.items()
                         if comp == components[joint.child])
        found.append((joint, members))
    return found


def self_joints(robot: Robot) -> list[Joint]:
    """Joints whose parent and child are the same (defined) link."""
    links = {link.name for link in robot.links}
    return [joint for joint in robot.joints
            if joint.parent in links and joint.parent == joint.child]


def _strongly_connected(edges: list[Joint]) -> dict[str, int]:
    """Tarjan's algorithm, iterative: link name -> component id (links on edges only)."""
    graph: dict[str, list[str]] = defaultdict(list)
    for joint in edges:
        graph[joint.parent].append(joint.child)
        graph.setdefault(joint.child, [])
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    component: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    counter = 0
    for start in graph:
        if start in index:
            continue
        work = [(start, 0)]
        while work:
            node, position = work.pop()
            if position == 0:
                index[node] = low[node] = counter
                counter += 1
                stack.append(node)
                on_stack.add(node)
            successors = graph[node]
            if position < len(successors):
                work.append((node, position + 1))
                nxt = successors[position]
                if nxt not in index:
                    work.append((nxt, 0))
                elif nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
                continue
            if low[node] == index[node]:
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component[member] = index[node]
                    if member == node:
                        break
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
    return component


def _first_joint_per_cycle(edges: list[Joint], components: dict[str, int]) -> list[Joint]:
    """The first joint (document order) inside each component of two or more links."""
    sizes: dict[int, int] = defaultdict(int)
    for comp in components.values():
        sizes[comp] += 1
    reported: set[int] = set()
    firsts = []
    for joint in edges:
        comp = components[joint.parent]
        if (joint.parent != joint.child and comp == components[joint.child]
                and sizes[comp] > 1 and comp not in reported):
            reported.add(comp)
            firsts.append(joint)
    return firsts


def tree_problem(robot: Robot) -> tuple[str, str, Provenance | None] | None:
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
    heads = [link for link in robot.links if link.name not in parents]
    if len(heads) != 1:
        what = "no root link (a cycle)" if not heads else \
            "several root links: " + ", ".join(link.name for link in heads)
        return f"the links form {what}", f"robot:{robot.name}", robot.where
    return None


# --- mimic joints -------------------------------------------------------------------------

def mimicking(robot: Robot) -> Iterator[tuple[Joint, str]]:
    """(joint, the name it mimics) for each joint with a `<mimic joint=...>`, document order."""
    for joint in robot.joints:
        if joint.mimic is not None and joint.mimic.joint:
            yield joint, joint.mimic.joint


def mimic_value(joint: Joint, leader: float) -> float:
    """A mimic joint's value when the joint it follows is at `leader` (rad or m):
    `multiplier * leader + offset` (multiplier 1 and offset 0 when not given)."""
    mimic = joint.mimic
    if mimic is None:
        return leader
    return (mimic.multiplier if mimic.multiplier is not None else 1.0) * leader \
        + (mimic.offset if mimic.offset is not None else 0.0)


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
    """Every one-variable joint's value: given ones, defaults for the rest, mimic joints
    followed (chains too; a joint in a mimic cycle keeps its own default).

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
        if joint is None or joint.type not in SCALAR_TYPES:
            moving = sorted((n for n, j in joints.items()
                             if j.type in SCALAR_TYPES and j.mimic is None),
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
                and joints[mimic.joint].type in SCALAR_TYPES:
            value = mimic_value(joint, value_of(mimic.joint, chain + (name,)))
        else:
            value = float(given.get(name, default_value(joint)))
        resolved[name] = value
        return value

    for name, joint in joints.items():
        if joint.type in SCALAR_TYPES:
            value_of(name, ())
    return resolved


# --- forward kinematics (numpy) -----------------------------------------------------------

def axis_rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """The 3x3 rotation by `angle` (rad) about the unit vector `axis` (Rodrigues)."""
    import numpy as np

    x, y, z = axis
    c, s = math.cos(angle), math.sin(angle)
    t = 1.0 - c
    return np.array([[t * x * x + c, t * x * y - s * z, t * x * z + s * y],
                     [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
                     [t * x * z - s * y, t * y * z + s * x, t * z * z + c]])


def joint_motion(joint: Joint, value: float) -> np.ndarray:
    """The 4x4 motion of a joint at `value` (rad or m), applied after its origin: about
    (revolute, continuous) or along (prismatic) its unit axis; identity for other types and
    for a zero or non-finite axis."""
    import numpy as np

    motion = np.identity(4)
    if joint.type not in SCALAR_TYPES or value == 0.0:
        return motion
    axis = np.asarray(joint.axis or DEFAULT_AXIS, dtype=float)
    norm = float(np.linalg.norm(axis))
    if not math.isfinite(norm) or norm == 0.0:
        return motion  # a zero axis is a lint finding; leave the joint unmoved
    axis = axis / norm
    if joint.type == "prismatic":
        motion[:3, 3] = axis * value
    else:
        motion[:3, :3] = axis_rotation(axis, value)
    return motion


@dataclass(frozen=True, eq=False)
class JointChain:
    """The tree in walking order, as plain arrays (picklable), for forward kinematics of many
    configurations at once.

    Attributes:
        links: link names; parents before children, each root first in its tree.
        parent: per link, the index of its parent link (-1 for a root).
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


def joint_chain(robot: Robot, columns: Sequence[str]) -> JointChain:
    """The walking order of `robot`'s tree (breadth first from each root; the first joint that
    reaches a link places it); `columns` names the joints of a positions array. Links that no
    root reaches (in a kinematic loop) are left out."""
    import numpy as np

    column_of = {name: k for k, name in enumerate(columns)}
    children = children_of(robot)
    links: list[str] = []
    parent: list[int] = []
    origin: list[np.ndarray] = []
    axis: list[np.ndarray] = []
    prismatic: list[bool] = []
    column: list[int] = []
    index: dict[str, int] = {}
    for root in roots(robot):
        if root.name in index:
            continue
        index[root.name] = len(links)
        links.append(root.name)
        parent.append(-1)
        origin.append(np.identity(4))
        axis.append(np.zeros(3))
        prismatic.append(False)
        column.append(-1)
        queue = deque([root.name])
        while queue:
            name = queue.popleft()
            for joint in children.get(name, ()):
                if joint.child in index:
                    continue
                index[joint.child] = len(links)
                links.append(joint.child)
                parent.append(index[name])
                origin.append(pose_matrix(joint.origin))
                vector = np.asarray(joint.axis or DEFAULT_AXIS, dtype=float)
                norm = float(np.linalg.norm(vector))
                moving = joint.type in SCALAR_TYPES and joint.name in column_of \
                    and math.isfinite(norm) and norm > 0.0
                axis.append(vector / norm if moving else np.zeros(3))
                prismatic.append(joint.type == "prismatic")
                column.append(column_of[joint.name] if moving else -1)
                queue.append(joint.child)
    return JointChain(tuple(links), np.asarray(parent, dtype=int), np.asarray(origin),
                      np.asarray(axis), np.asarray(prismatic, dtype=bool),
                      np.asarray(column, dtype=int))


def link_frames(chain: JointChain, positions: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """World frames of every link of `chain` for every row of `positions`: each joint places
    its child by `origin`, then moves it about (revolute, continuous) or along (prismatic)
    its unit axis, as Pinocchio's URDF reader does; fixed joints only place.

    Args:
        chain: from `joint_chain`.
        positions: (n, columns) joint positions, rad or m.

    Returns:
        Rotations (n, links, 3, 3) and translations (n, links, 3), m.
    """
    import numpy as np

    count = len(positions)
    rotations = np.empty((count, len(chain.links), 3, 3))
    translations = np.empty((count, len(chain.links), 3))
    identity = np.identity(3)
    for k in range(len(chain.links)):
        origin, parent = chain.origin[k], chain.parent[k]
        if parent < 0:
            rotation = np.broadcast_to(origin[:3, :3], (count, 3, 3))
            translation = np.broadcast_to(origin[:3, 3], (count, 3))
        else:
            rotation = rotations[:, parent] @ origin[:3, :3]
            translation = rotations[:, parent] @ origin[:3, 3] + translations[:, parent]
        if chain.column[k] >= 0:
            value, a = positions[:, chain.column[k]], chain.axis[k]
            if chain.prismatic[k]:
                translation = translation + rotation @ a * value[:, None]
            else:
                c, s = np.cos(value)[:, None, None], np.sin(value)[:, None, None]
                cross = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
                motion = c * identity + s * cross + (1.0 - c) * np.outer(a, a)
                rotation = rotation @ motion
        rotations[:, k] = rotation
        translations[:, k] = translation
    return rotations, translations


def poses_at(robot: Robot, q: Mapping[str, float] | None = None) -> dict[str, np.ndarray]:
    """World transform (4x4) of every link for a complete configuration (as returned by
    `configuration`: mimic joints already resolved; missing joints taken as 0).

    Root links (no parent joint) sit at the identity; the tree is walked breadth first, the
    first joint reaching a link places it (`joint_chain`, `link_frames`). A link that no root
    reaches (in a kinematic loop) is placed at the identity too, and logged. Fixed, floating
    and planar joints are placed at their origin.
    """
    import numpy as np

    q = q or {}
    columns = [joint.name for joint in robot.joints if joint.type in SCALAR_TYPES]
    chain = joint_chain(robot, columns)
    positions = np.array([[float(q.get(name, 0.0)) for name in columns]])
    rotations, translations = link_frames(chain, positions)
    poses: dict[str, np.ndarray] = {}
    for k, name in enumerate(chain.links):
        pose = np.identity(4)
        pose[:3, :3] = rotations[0, k]
        pose[:3, 3] = translations[0, k]
        poses[name] = pose
    for link in robot.links:
        if link.name not in poses:
            log.info("link '%s' is not reached from a root link; placed at the origin",
                     link.name)
            poses[link.name] = np.identity(4)
    return poses


def link_transforms(robot: Robot, values: Mapping[str, float] | None = None
                    ) -> dict[str, np.ndarray]:
    """World transform (4x4) of every link at a configuration (`configuration` of `values`:
    defaults for joints not given, mimic joints followed); see `poses_at`."""
    return poses_at(robot, configuration(robot, values))
