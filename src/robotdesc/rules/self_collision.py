"""Self-collision rules (K2xx of the kinematics family): link pairs whose collision geometry
overlaps in the default configuration (K201), and pairs in contact by design (K203).

Both need Pinocchio and coal (`pip install '.[kinematics]'`); without them they are skipped
with a logged note. They share one computation per robot (`self_collisions`): the pairs
colliding at MoveIt's default configuration, split into those in contact at every sampled
configuration, those touching only because joints sit at a limit, and those whose relative
pose one degree of freedom decides.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

from robotdesc.diagnostics import Finding, Severity
from robotdesc.inertia.mesh_access import MeshAccess
from robotdesc.kinematics.build import KinematicBuildError
from robotdesc.kinematics.configuration import (
    default_configuration,
    follow_mimics,
    independent_joints,
    joint_range,
)
from robotdesc.kinematics.optional import pinocchio_or_note
from robotdesc.kinematics.urdf_text import MeshPath
from robotdesc.mesh.context import MeshContext
from robotdesc.mesh.settings import MeshSettings
from robotdesc.model import tree
from robotdesc.model.elements import Joint, Robot
from robotdesc.rules.registry import RuleContext, rule

if TYPE_CHECKING:
    from robotdesc.srdf.matrix import PreparedScene

FAMILY = "kinematics"

Pair = tuple[str, str]
#: Joint types whose position is not one variable a linkage could share.
_NOT_ONE_DOF = ("fixed", "floating", "planar")
#: Joints at a limit in the default configuration are moved this fraction of their range
#: inward to tell a contact at the limit (a closed gripper) from an overlap.
INWARD_FRACTION = 0.1


@dataclass(frozen=True)
class SelfCollisions:
    """The link pairs in collision at the default configuration, and why some are by design.

    Attributes:
        colliding: non-adjacent pairs whose collision geometry overlaps there, in order.
        always: those that also collide at every sampled configuration (K203, "Always").
        at_default: those in contact because joints sit at a limit, or whose relative pose
            one degree of freedom decides (K203, "Default").
    """

    colliding: tuple[Pair, ...]
    always: frozenset[Pair]
    at_default: frozenset[Pair]

    def overlaps(self) -> list[Pair]:
        """The colliding pairs not in contact by design: K201's."""
        return [pair for pair in self.colliding
                if pair not in self.always and pair not in self.at_default]


@rule("K201", "self-collision-at-default", family=FAMILY, severity=Severity.WARNING,
      needs=("meshes", "pinocchio"), opt_in=True)
def self_collision_at_default(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds two links, not adjacent, whose collision geometry overlaps in the default
    configuration (each joint at 0, or mid-range when 0 is outside its limits, as MoveIt sets
    it).

    Adjacency is MoveIt Setup Assistant's: links joined by fixed joints are one rigid body and
    never reported; links whose bodies a joint connects (directly, or through bodies without
    collision geometry) are adjacent. A pair that also collides at every sampled
    configuration (links in contact by design, such as a mimic-coupled linkage), that
    touches only because joints sit at a limit in the default configuration (a gripper
    closed at 0, a folded rest pose) and parts once they move inward, or whose relative pose
    one degree of freedom decides (a joint and those that mimic it: the fingers and knuckles
    of a gripper touching at its default opening), is K203's.

    Opt-in (`--select K201`): on real packages about a third of its findings are contacts
    by design that no rule can yet tell from an overlap (two-finger grippers closed at 0 with
    independent fingers, a fabric bellows through a base, legs together at rest); see
    docs/precision.md. `robotdesc srdf` writes the whole collision matrix either way.

    Why is this bad?
    A robot that starts in self-collision cannot be planned for: MoveIt rejects the start
    state, and a simulator pushes the links apart at spawn. Usually a collision mesh is too
    big (a visual mesh reused, a hull over a concave part) or an origin is wrong. If the
    overlap is real and harmless, disable the pair in the SRDF (`robotdesc srdf`).

    Example
    ```xml
    <robot name="arm">
      <link name="base"><collision><geometry><box size="0.4 0.4 0.4"/></geometry></collision></link>
      <link name="upper"><collision><geometry><box size="0.1 0.1 0.3"/></geometry></collision></link>
      <link name="fore"><collision><origin xyz="0 0 -0.45"/>
        <geometry><box size="0.1 0.1 0.3"/></geometry></collision></link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="upper"/>
        <origin xyz="0 0 0.3"/></joint>
      <joint name="elbow" type="continuous"><parent link="upper"/><child link="fore"/>
        <origin xyz="0 0 0.3"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"><collision><geometry><box size="0.4 0.4 0.4"/></geometry></collision></link>
      <link name="upper"><collision><geometry><box size="0.1 0.1 0.3"/></geometry></collision></link>
      <link name="fore"><collision><origin xyz="0 0 0.15"/>
        <geometry><box size="0.1 0.1 0.3"/></geometry></collision></link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="upper"/>
        <origin xyz="0 0 0.3"/></joint>
      <joint name="elbow" type="continuous"><parent link="upper"/><child link="fore"/>
        <origin xyz="0 0 0.3"/></joint>
    </robot>
    ```
    """
    found = self_collisions(robot, ctx, "K201")
    if found is None:
        return
    for first, second in found.overlaps():
        link = robot.link(second)
        yield Finding(f"links '{first}' and '{second}' collide in the default configuration "
                      "(they are not adjacent, even with fixed joints merged)",
                      link.where if link else None, f"link:{second}")


#: The last robot's self-collisions (K201 and K203 share them; the lint driver runs the
#: rules of one robot one after the other).
_LAST: dict[str, tuple[Robot, SelfCollisions]] = {}


def self_collisions(robot: Robot, ctx: RuleContext, code: str) -> SelfCollisions | None:
    """The robot's self-collisions at the default configuration, or None when the check
    cannot run (fewer than two links with collision geometry, no Pinocchio: noted once for
    `code`, a model Pinocchio refuses: K101's or a structural rule's)."""
    cached = _LAST.get("last")
    if cached is not None and cached[0] is robot:
        return cached[1]
    if sum(tree.has_collision(link) for link in robot.links) < 2:
        return None
    if not pinocchio_or_note(code):
        return None
    from robotdesc.srdf.matrix import always_in_contact, default_collisions, prepare_scene

    try:
        prepared = prepare_scene(robot, mesh_path(robot, ctx))
    except KinematicBuildError:
        return None
    colliding = default_collisions(prepared)
    always = set(always_in_contact(prepared, colliding))
    rest = [pair for pair in colliding if pair not in always]
    at_default = contact_at_limits(robot, prepared, rest) | one_dof_pairs(robot, rest)
    result = SelfCollisions(tuple(colliding), frozenset(always), frozenset(at_default))
    _LAST["last"] = (robot, result)
    return result


def contact_at_limits(robot: Robot, prepared: PreparedScene, pairs: list[Pair]) -> set[Pair]:
    """The pairs that part when every independent joint sitting at a limit in the default
    configuration moves `INWARD_FRACTION` of its range inward (mimic joints following)."""
    from robotdesc.srdf.matrix import collisions_at

    if not pairs:
        return set()
    default = default_configuration(robot)
    moved: dict[str, float] = {}
    for joint in independent_joints(robot):
        found = joint_range(joint)
        value = default.get(joint.name)
        if found is None or not found.bounded or value is None:
            continue
        span = found.upper - found.lower
        if span <= 0:
            continue
        if abs(value - found.lower) <= 1e-9 * span:
            moved[joint.name] = value + INWARD_FRACTION * span
        elif abs(value - found.upper) <= 1e-9 * span:
            moved[joint.name] = value - INWARD_FRACTION * span
    if not moved:
        return set()
    drivers = {j.name: default.get(j.name, 0.0) for j in independent_joints(robot)}
    configuration = follow_mimics(robot, {**drivers, **moved})
    still = set(collisions_at(prepared, configuration, list(pairs)))
    return {pair for pair in pairs if pair not in still}


def one_dof_pairs(robot: Robot, pairs: list[Pair]) -> set[Pair]:
    """The pairs whose relative pose one degree of freedom decides: every moving joint on the
    tree path between them is one joint or mimics it (the fingers or knuckles of a gripper).

    Such a pair in contact at the default configuration, but not at every sampled one, is a
    linkage touching at its default position (a gripper closed at 0): K203's "Default", not
    an overlap to fix.
    """
    parent_joint = tree.parent_joint_of(robot)
    joints = {joint.name: joint for joint in robot.joints}

    def driver(joint: Joint) -> str:
        seen = {joint.name}
        while joint.mimic is not None and joint.mimic.joint in joints \
                and joint.mimic.joint not in seen:
            joint = joints[joint.mimic.joint]
            seen.add(joint.name)
        return joint.name

    def path_up(link: str) -> list[str]:
        chain, seen = [link], {link}
        while link in parent_joint and parent_joint[link].parent not in seen:
            link = parent_joint[link].parent
            chain.append(link)
            seen.add(link)
        return chain

    found = set()
    for first, second in pairs:
        up_first, up_second = path_up(first), path_up(second)
        common = set(up_first) & set(up_second)
        if not common:
            continue
        below = [link for link in up_first if link not in common] + \
            [link for link in up_second if link not in common]
        drivers = {driver(parent_joint[link]) for link in below
                   if parent_joint[link].type not in _NOT_ONE_DOF}
        if len(drivers) == 1:
            found.add((first, second))
    return found


@rule("K203", "links-always-in-contact", family=FAMILY, severity=Severity.INFO,
      needs=("meshes", "pinocchio"), opt_in=True)
def links_always_in_contact(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds pairs of links, not adjacent, whose collision geometry overlaps at the default
    configuration and at every sampled configuration of the joints: links in contact by
    design (the bars of a mimic-coupled four-bar linkage, a hand's safety box). They are
    reported once, with the SRDF lines that disable them. Opt-in (info): the contacts are
    by design; turn it on to write a MoveIt SRDF's disabled pairs.

    Pairs in contact at the default configuration only because joints sit at a limit there
    (fingers of a gripper closed at 0, an arm folded into its rest pose), which part when
    those joints move a tenth of their range inward, and pairs whose relative pose one
    degree of freedom decides (a joint and the joints that mimic it: a gripper's fingers and
    knuckles), are reported in a second finding: MoveIt's Setup Assistant disables them with
    reason "Default".

    Why is this bad?
    It is not a mistake in the URDF, but MoveIt treats the robot as always in
    self-collision until the SRDF disables these pairs (`robotdesc srdf` writes the whole
    matrix).

    Example
    ```xml
    <!-- two fingers whose collision boxes overlap at every opening -->
    <robot name="gripper">
      <link name="palm"/>
      <link name="left"><collision><geometry><box size="0.1 0.02 0.05"/></geometry></collision></link>
      <link name="right"><collision><geometry><box size="0.1 0.02 0.05"/></geometry></collision></link>
      <joint name="left_joint" type="prismatic"><parent link="palm"/><child link="left"/>
        <axis xyz="1 0 0"/><limit lower="0" upper="0.01" effort="10" velocity="0.1"/></joint>
      <joint name="right_joint" type="prismatic"><parent link="palm"/><child link="right"/>
        <axis xyz="-1 0 0"/><limit lower="0" upper="0.01" effort="10" velocity="0.1"/>
        <mimic joint="left_joint"/></joint>
    </robot>
    ```

    Use instead (in the SRDF):
    ```xml
    <disable_collisions link1="left" link2="right" reason="Always"/>
    ```
    """
    found = self_collisions(robot, ctx, "K203")
    if found is None:
        return
    default_what = ("are in contact at the default configuration of a linkage or joints at "
                    "a limit (a closed gripper, a folded rest pose), and part when those "
                    "joints move")
    for chosen, reason, what in (
            (found.always, "Always", "are in contact at every sampled configuration (by design)"),
            (found.at_default, "Default", default_what)):
        pairs = [pair for pair in found.colliding if pair in chosen]
        if not pairs:
            continue
        lines = [f'<disable_collisions link1="{a}" link2="{b}" reason="{reason}"/>'
                 for a, b in pairs]
        link = robot.link(pairs[0][1])
        yield Finding(f"{len(pairs)} link pair(s) {what}: "
                      f"{', '.join(f'{a}/{b}' for a, b in pairs)}; disable them in the "
                      f"SRDF: {'; '.join(lines)}", link.where if link else robot.where,
                      f"link:{pairs[0][1]}", "\n".join(lines))


def mesh_path(robot: Robot, ctx: RuleContext) -> MeshPath:
    """`<mesh>` -> file, through the mesh layer: the lint's mesh context (it knows the
    --package-path folders and the config), or a new one for the robot's own file."""
    meshes: MeshAccess = ctx.meshes if ctx.meshes is not None else \
        MeshContext.for_file(robot, robot.source or ".", MeshSettings())
    return lambda mesh: meshes.lookup(mesh).resolution.path
