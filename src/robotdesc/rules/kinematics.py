"""Kinematics rules (K1xx: the model as Pinocchio and simulators see it; K2xx: self-collision).

K101 and K201 need Pinocchio (`pip install 'robotdesc[kinematics]'`); without it they are
skipped with a logged note. The others are pure checks of the model.
"""

from __future__ import annotations

import logging
import re
from collections.abc import Iterator
from dataclasses import dataclass

from robotdesc.diagnostics import Finding, Severity
from robotdesc.kinematics import tree
from robotdesc.kinematics.configuration import joint_range, zero_configuration
from robotdesc.kinematics.mirror import mirror_pairs
from robotdesc.model.elements import Joint, Robot
from robotdesc.rules.registry import RuleContext, rule

FAMILY = "kinematics"
log = logging.getLogger(__name__)

#: urdfdom refusals that a model rule already reports (reason pattern -> that rule's code).
_EXPLAINED = (
    (re.compile(r"does not specify limits"), "J102"),
    (re.compile(r"has no known type"), "J101"),
    (re.compile(r"not found|Failed to build tree"), "S108"),
    (re.compile(r"root link", re.IGNORECASE), "S101/S102"),
    (re.compile(r"is not unique"), "S106/S107"),
    (re.compile(r"No link elements"), "S001"),
)
_NOTED: set[str] = set()


def _pinocchio_or_note(code: str) -> bool:
    """True when Pinocchio is importable; otherwise log (once per rule) why `code` is skipped."""
    from robotdesc.kinematics.optional import PINOCCHIO_HINT, pinocchio_available

    if pinocchio_available():
        return True
    if code not in _NOTED:
        _NOTED.add(code)
        log.warning("%s skipped: Pinocchio is not installed; %s", code, PINOCCHIO_HINT)
    return False


@rule("K101", "pinocchio-cannot-build", family=FAMILY, severity=Severity.ERROR,
      needs=("pinocchio",))
def pinocchio_cannot_build(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a description Pinocchio (urdfdom) refuses to load, for a reason no structural rule
    reports; the finding quotes Pinocchio's reason at the element it names.

    Refusals that a model rule already explains (a revolute joint without `<limit>`, an
    unknown joint type, a missing link, several roots, a duplicate name) are left to that rule.

    Why is this bad?
    Pinocchio, MoveIt, robot_state_publisher and every other urdfdom-based tool refuse the
    whole model: nothing downstream loads.

    Example
    ```xml
    <!-- a refusal quoted from Pinocchio, at the joint it names -->
    <joint name="knee" type="revolute"><parent link="thigh"/><child link="shin"/></joint>
    ```

    Use instead (whatever Pinocchio's reason asks for, here a `<limit>`):
    ```xml
    <joint name="knee" type="revolute"><parent link="thigh"/><child link="shin"/>
      <limit lower="0" upper="2.4" effort="40" velocity="6"/></joint>
    ```
    """
    if robot.value_issues or not _pinocchio_or_note("K101"):
        return  # unreadable values are S110's; Pinocchio would refuse them too
    from robotdesc.kinematics.build import KinematicBuildError, build_model

    try:
        build_model(robot)
    except KinematicBuildError as error:
        problem = error.problem
        if not problem.from_pinocchio or any(pattern.search(problem.reason) for pattern, _ in _EXPLAINED):
            return
        yield Finding(f"Pinocchio cannot build the model: {problem.reason}",
                      problem.where or robot.where, problem.element or f"robot:{robot.name}")


@rule("K102", "zero-configuration-outside-limits", family=FAMILY, severity=Severity.WARNING)
def zero_configuration_outside_limits(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a joint whose limits exclude 0, the position every joint takes in the zero
    (neutral) configuration; mimic joints are checked at the position their driver's 0 implies.

    Why is this bad?
    Pinocchio's `neutral()`, a Gazebo or MuJoCo spawn and ros2_control's default initial state
    all put the joint at 0, outside its range: controllers start by fighting a limit, and
    planners reject the start state. MoveIt uses the middle of the range instead, so the two
    "default" poses differ. Set an initial position, or make 0 reachable.

    Example
    ```xml
    <robot name="arm">
      <link name="upper"/><link name="fore"/>
      <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/>
        <limit lower="-3.07" upper="-0.07" effort="87" velocity="2.2"/></joint>
    </robot>
    ```

    Use instead (a range that contains 0, when the mechanism allows it):
    ```xml
    <robot name="arm">
      <link name="upper"/><link name="fore"/>
      <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/>
        <limit lower="-3.07" upper="0.0" effort="87" velocity="2.2"/></joint>
    </robot>
    ```
    """
    zero = zero_configuration(robot)
    for joint in robot.joints:
        found = joint_range(joint)
        if found is None or not found.bounded or joint.name not in zero:
            continue
        position = zero[joint.name]
        if not found.lower - 1e-9 <= position <= found.upper + 1e-9:
            unit = "m" if joint.type == "prismatic" else "rad"
            how = "its mimic driver at 0 puts it at" if joint.mimic else "the zero configuration puts it at"
            yield Finding(f"joint '{joint.name}': {how} {position:g} {unit}, outside its limits "
                          f"[{found.lower:g}, {found.upper:g}] {unit}",
                          (joint.limit.where if joint.limit else None) or joint.where,
                          f"joint:{joint.name}")


@dataclass(frozen=True)
class MassRatioOptions:
    """Options of K103.

    Attributes:
        max_ratio: largest allowed ratio of the heavier to the lighter body across a joint.
        min_mass: bodies lighter than this (kg) are left to the inertia rules.
    """

    max_ratio: float = 100.0
    min_mass: float = 1e-6


@rule("K103", "mass-ratio-across-joint", family=FAMILY, severity=Severity.WARNING,
      options=MassRatioOptions)
def mass_ratio_across_joint(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a moving joint whose two bodies' masses differ by more than `max_ratio`.

    Bodies are compared as simulators build them: links joined by fixed joints are merged
    into one body first.

    Why is this bad?
    Large mass ratios between connected bodies make the constraint solvers of ODE, Bullet,
    PhysX and MuJoCo converge slowly: joints stretch, jitter or explode unless the time step
    shrinks. A 2 g finger on a 20 kg arm is a classic cause.

    Example
    ```xml
    <robot name="arm">
      <link name="base"><inertial><mass value="50"/>
        <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
      <link name="tip"><inertial><mass value="0.01"/>
        <inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/></inertial></link>
      <joint name="tip_joint" type="continuous"><parent link="base"/><child link="tip"/></joint>
    </robot>
    ```

    Use instead (realistic masses, or a fixed joint for a part that does not move):
    ```xml
    <robot name="arm">
      <link name="base"><inertial><mass value="5"/>
        <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
      <link name="tip"><inertial><mass value="0.2"/>
        <inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>
      <joint name="tip_joint" type="continuous"><parent link="base"/><child link="tip"/></joint>
    </robot>
    ```
    """
    options = ctx.options or MassRatioOptions()
    head = tree.body_of(robot)
    masses = tree.body_masses(robot)
    for joint in robot.joints:
        if joint.type not in tree.MOVING_TYPES or joint.parent not in head or joint.child not in head:
            continue
        parent_body, child_body = head[joint.parent], head[joint.child]
        parent_mass, child_mass = masses.get(parent_body, 0.0), masses.get(child_body, 0.0)
        light, heavy = sorted((parent_mass, child_mass))
        if light < options.min_mass or heavy / light <= options.max_ratio:
            continue
        yield Finding(f"joint '{joint.name}' connects bodies of {parent_mass:g} kg "
                      f"('{parent_body}') and {child_mass:g} kg ('{child_body}'): ratio "
                      f"{heavy / light:.0f} > {options.max_ratio:g}",
                      joint.where, f"joint:{joint.name}")


@dataclass(frozen=True)
class MirrorOptions:
    """Options of K104.

    Attributes:
        length_tolerance: largest difference of mirrored origin coordinates (m), compared
            by absolute value so that either mirror plane matches.
        angle_tolerance: largest difference of mirrored angles and limits (rad).
    """

    length_tolerance: float = 0.001
    angle_tolerance: float = 0.01


@rule("K104", "mirrored-joints-differ", family=FAMILY, severity=Severity.WARNING,
      options=MirrorOptions)
def mirrored_joints_differ(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a left/right pair of joints (left_/right_, l_/r_, _l/_r) whose type, origin,
    axis or range of motion differ beyond the tolerances, allowing for the mirror.

    Origins and axes are compared by the absolute value of each coordinate, limits as the
    range [lower, upper] or its mirror [-upper, -lower].

    Why is this bad?
    The two sides of a symmetric robot are usually one macro called twice; a difference is
    a typo in one call (a sign, a swapped limit, a digit), and the robot walks or grasps
    crookedly in ways a controller tuned on one side will not expect.

    Example
    ```xml
    <robot name="biped">
      <link name="pelvis"/><link name="left_thigh"/><link name="right_thigh"/>
      <joint name="left_hip" type="revolute"><parent link="pelvis"/><child link="left_thigh"/>
        <origin xyz="0 0.1 0"/><axis xyz="0 1 0"/>
        <limit lower="-1.5" upper="0.5" effort="100" velocity="5"/></joint>
      <joint name="right_hip" type="revolute"><parent link="pelvis"/><child link="right_thigh"/>
        <origin xyz="0 -0.12 0"/><axis xyz="0 1 0"/>
        <limit lower="-1.5" upper="0.5" effort="100" velocity="5"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="biped">
      <link name="pelvis"/><link name="left_thigh"/><link name="right_thigh"/>
      <joint name="left_hip" type="revolute"><parent link="pelvis"/><child link="left_thigh"/>
        <origin xyz="0 0.1 0"/><axis xyz="0 1 0"/>
        <limit lower="-1.5" upper="0.5" effort="100" velocity="5"/></joint>
      <joint name="right_hip" type="revolute"><parent link="pelvis"/><child link="right_thigh"/>
        <origin xyz="0 -0.1 0"/><axis xyz="0 1 0"/>
        <limit lower="-1.5" upper="0.5" effort="100" velocity="5"/></joint>
    </robot>
    ```
    """
    options = ctx.options or MirrorOptions()
    for first, second in mirror_pairs(joint.name for joint in robot.joints):
        a, b = robot.joint(first), robot.joint(second)
        reason = _mirror_difference(a, b, options)
        if reason:
            yield Finding(f"mirrored joints '{first}' and '{second}' differ: {reason}",
                          b.where, f"joint:{second}")


def _mirror_difference(a: Joint, b: Joint, options: MirrorOptions) -> str:
    if a.type != b.type:
        return f"type {a.type} vs {b.type}"
    length, angle = options.length_tolerance, options.angle_tolerance
    for what, u, v, tolerance in (("origin xyz", a.origin.xyz, b.origin.xyz, length),
                                  ("origin rpy", a.origin.rpy, b.origin.rpy, angle),
                                  ("axis", a.axis or (1.0, 0.0, 0.0), b.axis or (1.0, 0.0, 0.0),
                                   1e-6)):
        gap = max(abs(abs(x) - abs(y)) for x, y in zip(u, v))
        if gap > tolerance:
            return (f"{what} ({_vector(u)}) vs ({_vector(v)}), |difference| {gap:g} > "
                    f"{tolerance:g}")
    range_a, range_b = joint_range(a), joint_range(b)
    if range_a and range_b and range_a.bounded and range_b.bounded:
        tolerance = length if a.type == "prismatic" else angle
        same = max(abs(range_a.lower - range_b.lower), abs(range_a.upper - range_b.upper))
        mirrored = max(abs(range_a.lower + range_b.upper), abs(range_a.upper + range_b.lower))
        if min(same, mirrored) > tolerance:
            return (f"limits [{range_a.lower:g}, {range_a.upper:g}] vs "
                    f"[{range_b.lower:g}, {range_b.upper:g}]")
    return ""


def _vector(values) -> str:
    return " ".join(f"{v:g}" for v in values)


@dataclass(frozen=True)
class MirrorMassOptions:
    """Options of K105.

    Attributes:
        relative_tolerance: largest relative difference of mirrored masses (0.05 = 5 %).
    """

    relative_tolerance: float = 0.05


@rule("K105", "mirrored-masses-differ", family=FAMILY, severity=Severity.WARNING,
      options=MirrorMassOptions)
def mirrored_masses_differ(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a left/right pair of links (left_/right_, l_/r_, _l/_r) whose masses differ by
    more than `relative_tolerance`.

    Why is this bad?
    Mirrored parts of a symmetric robot weigh the same; a different mass is a typo in one
    macro call or a CAD export of the wrong part. The robot's centre of mass shifts to one
    side, and balance or gravity compensation tuned in simulation fails on hardware.

    Example
    ```xml
    <robot name="biped">
      <link name="pelvis"/>
      <link name="l_foot"><inertial><mass value="1.2"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <link name="r_foot"><inertial><mass value="12"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <joint name="l_ankle" type="fixed"><parent link="pelvis"/><child link="l_foot"/></joint>
      <joint name="r_ankle" type="fixed"><parent link="pelvis"/><child link="r_foot"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="biped">
      <link name="pelvis"/>
      <link name="l_foot"><inertial><mass value="1.2"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <link name="r_foot"><inertial><mass value="1.2"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <joint name="l_ankle" type="fixed"><parent link="pelvis"/><child link="l_foot"/></joint>
      <joint name="r_ankle" type="fixed"><parent link="pelvis"/><child link="r_foot"/></joint>
    </robot>
    ```
    """
    options = ctx.options or MirrorMassOptions()
    for first, second in mirror_pairs(link.name for link in robot.links):
        a, b = robot.link(first), robot.link(second)
        mass_a, mass_b = tree.link_mass(a), tree.link_mass(b)
        heavy = max(mass_a, mass_b)
        if heavy <= 0 or abs(mass_a - mass_b) <= options.relative_tolerance * heavy:
            continue
        where = (b.inertial.where if b.inertial else None) or b.where
        yield Finding(f"mirrored links '{first}' and '{second}' weigh {mass_a:g} kg and "
                      f"{mass_b:g} kg ({abs(mass_a - mass_b) / heavy:.0%} apart, tolerance "
                      f"{options.relative_tolerance:.0%})", where, f"link:{second}")


@rule("K201", "self-collision-at-default", family=FAMILY, severity=Severity.WARNING,
      needs=("meshes", "pinocchio"))
def self_collision_at_default(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds two links, not connected by a joint, whose collision geometry overlaps in the
    default configuration (each joint at 0, or mid-range when 0 is outside its limits, as
    MoveIt sets it).

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
    if sum(tree.has_collision(link) for link in robot.links) < 2:
        return
    if not _pinocchio_or_note("K201"):
        return
    from robotdesc.kinematics.build import KinematicBuildError
    from robotdesc.srdf.matrix import default_collisions, prepare_scene

    try:
        prepared = prepare_scene(robot, _mesh_path(robot, ctx))
    except KinematicBuildError:
        return  # K101 or a structural rule reports it
    for first, second in default_collisions(prepared):
        link = robot.link(second)
        yield Finding(f"links '{first}' and '{second}' collide in the default configuration "
                      "(they are not connected by a joint)", link.where if link else None,
                      f"link:{second}")


def _mesh_path(robot: Robot, ctx: RuleContext):
    """Resolve meshes through the lint's mesh context when there is one (it knows the
    --package-path folders and the config), else through the environment's package chain."""
    lookup = getattr(ctx.meshes, "lookup", None)
    if lookup is not None:
        return lambda mesh: lookup(mesh).resolution.path
    from robotdesc.kinematics.resolve import mesh_resolver, package_lookup

    return mesh_resolver(robot, package_lookup(robot.source or "."))


@rule("K202", "no-collision-geometry", family=FAMILY, severity=Severity.WARNING)
def no_collision_geometry(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a robot meant for simulation or planning (it has moving joints and declares
    masses) whose links have visual geometry but not a single `<collision>`.

    Why is this bad?
    Self-collision is checked between pairs of links with collision geometry; with none there
    is nothing to check. MoveIt plans straight through the robot itself, its Setup Assistant
    produces an empty collision matrix without saying why, and in a simulator the robot
    falls through the floor.

    Example
    ```xml
    <robot name="arm">
      <link name="base"><visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual></link>
      <link name="upper"><visual><geometry><box size="0.1 0.1 0.3"/></geometry></visual>
        <inertial><mass value="1"/>
          <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="upper"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"><visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual>
        <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
      <link name="upper"><visual><geometry><box size="0.1 0.1 0.3"/></geometry></visual>
        <collision><geometry><box size="0.1 0.1 0.3"/></geometry></collision>
        <inertial><mass value="1"/>
          <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="upper"/></joint>
    </robot>
    ```
    """
    if not any(joint.type in tree.MOVING_TYPES for joint in robot.joints):
        return
    if not any(tree.link_mass(link) > 0 for link in robot.links):
        return
    if any(link.collisions for link in robot.links):
        return
    visual = sum(1 for link in robot.links if any(v.geometry is not None for v in link.visuals))
    if visual >= 2:
        yield Finding(f"no link has a <collision> ({visual} links have visual geometry): the "
                      "self-collision matrix is empty, so MoveIt checks nothing",
                      robot.where, f"robot:{robot.name}")
