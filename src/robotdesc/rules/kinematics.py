"""Kinematics rules (K1xx: the model as Pinocchio and simulators see it; K202: no collision
geometry at all). The self-collision checks K201 and K203 are `rules/self_collision.py`.

K101 needs Pinocchio (`pip install '.[kinematics]'`); without it it is skipped with a logged
note. The others are pure checks of the model.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass

from robotdesc.diagnostics import Finding, Severity
from robotdesc.kinematics.configuration import joint_range, zero_configuration
from robotdesc.kinematics.mirror import mirror_pairs
from robotdesc.kinematics.optional import pinocchio_or_note
from robotdesc.kinematics.verdict import build_problem
from robotdesc.model import tree
from robotdesc.model.elements import Joint, Robot
from robotdesc.rules.registry import RuleContext, rule
from robotdesc.source import Provenance
from robotdesc.spatial import rpy_rotation

FAMILY = "kinematics"

#: urdfdom refusals that a model rule already reports (reason pattern -> that rule's code).
_EXPLAINED = (
    (re.compile(r"does not specify limits"), "J102"),
    (re.compile(r"has no known type"), "J101"),
    (re.compile(r"not found|Failed to build tree"), "S108"),
    (re.compile(r"root link", re.IGNORECASE), "S101/S102"),
    (re.compile(r"is not unique"), "S106/S107"),
    (re.compile(r"No link elements"), "S001"),
)


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
    if robot.value_issues or not pinocchio_or_note("K101"):
        return  # unreadable values are S110's; Pinocchio would refuse them too

    problem = build_problem(robot)  # a forked child's verdict when the lint started one
    if problem is None or not problem.from_pinocchio \
            or any(pattern.search(problem.reason) for pattern, _ in _EXPLAINED):
        return
    yield Finding(f"Pinocchio cannot build the model: {problem.reason}",
                  problem.where or robot.where, problem.element or f"robot:{robot.name}")


@rule("K102", "zero-configuration-outside-limits", family=FAMILY, severity=Severity.WARNING,
      opt_in=True)
def zero_configuration_outside_limits(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a joint whose limits exclude 0, the position every joint takes in the zero
    (neutral) configuration; mimic joints are checked at the position their driver's 0 implies.

    Opt-in: on real packages the range is by design (a knee that cannot straighten, Kinova's
    joint_2, whose Gazebo launch spawns the arm with `-J` at a pose inside the limits).

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
                          f"[{found.lower:g}, {found.upper:g}] {unit}; a Gazebo or MuJoCo spawn "
                          f"and ros2_control start it there unless an initial position is set",
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
      options=MassRatioOptions, opt_in=True)
def mass_ratio_across_joint(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a moving joint whose two bodies' masses differ by more than `max_ratio`.

    Off by default (`--select K103`): real robots have such ratios by design (a 50 g caster
    wheel under a 40 kg base, TIAGo and PMB2), so most findings on real packages are right
    masses; turn it on when tuning a model for an engine that struggles with them (ODE).

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
    options = ctx.options_as(MassRatioOptions)
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
                      f"('{parent_body}') and {child_mass:g} kg ('{child_body}'): the "
                      f"heavier is {_ratio(heavy / light, options.max_ratio)} times the lighter, "
                      f"above the threshold max_ratio = {options.max_ratio:g}",
                      joint.where, f"joint:{joint.name}")


def _ratio(ratio: float, threshold: float) -> str:
    """The ratio with enough digits to show that it is above `threshold`."""
    for digits in range(3, 10):
        text = f"{ratio:.{digits}g}"
        if float(text) > threshold:
            return text
    return repr(ratio)


@dataclass(frozen=True)
class MirrorOptions:
    """Options of K104.

    Attributes:
        length_tolerance: largest difference of mirrored origin coordinates (m), compared
            by absolute value so that either mirror plane matches.
        angle_tolerance: largest difference of mirrored angles and limits (rad).
        family_size: a family of more pairs than this (names equal but for their digits,
            differing in the same way, like the taxels of a skin) is reported once.
    """

    length_tolerance: float = 0.001
    angle_tolerance: float = 0.01
    family_size: int = 3


@rule("K104", "mirrored-joints-differ", family=FAMILY, severity=Severity.WARNING,
      options=MirrorOptions, opt_in=True)
def mirrored_joints_differ(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a left/right pair of joints (left_/right_, l_/r_, _l/_r) whose type, origin,
    axis or range of motion differ beyond the tolerances, allowing for the mirror.

    Origin positions and axes are compared by the absolute value of each coordinate; origin
    rotations as rotations (angles modulo 2*pi), mirrored through a plane and possibly turned
    by a half turn (a common way to build the other side); limits as the range
    [lower, upper] or its mirror [-upper, -lower]. A family of many pairs that differ in the
    same way (the taxels of a skin) is reported once.

    Off by default (`--select K104`): names are a weak sign of a mirror. On real packages
    most pairs it found were not mirrors of each other: Yaskawa's `joint_l`/`joint_r` are
    the L and R axes, and the front-left/front-right sensors of one foot or bumper sit where
    the hardware puts them, not symmetrically (docs/precision.md).

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
    options = ctx.options_as(MirrorOptions)
    families: dict[tuple[str, str], list[tuple[str, str, str]]] = {}
    for first, second in mirror_pairs(joint.name for joint in robot.joints):
        a, b = robot.joint(first), robot.joint(second)
        if a is None or b is None:
            continue
        reason = _mirror_difference(a, b, options)
        if reason:
            families.setdefault(_family_key(second, reason), []).append((first, second, reason))
    for (pattern, what), members in families.items():
        first, second, reason = members[0]
        if len(members) <= options.family_size:
            for first, second, reason in members:
                yield Finding(f"mirrored joints '{first}' and '{second}' differ: {reason}",
                              _joint_where(robot, second), f"joint:{second}")
            continue
        yield Finding(f"{len(members)} mirrored joint pairs named like '{pattern}' differ in "
                      f"{what}; the first: '{first}' and '{second}': {reason}",
                      _joint_where(robot, second), f"joint:{second}")


def _family_key(second: str, reason: str) -> tuple[str, str]:
    """Pairs named alike but for their digits, differing in the same way, form one family."""
    return _DIGITS.sub("#", second), reason.split(" (", 1)[0].split(" [", 1)[0]


def _joint_where(robot: Robot, name: str) -> Provenance | None:
    joint = robot.joint(name)
    return joint.where if joint is not None else None


#: Runs of digits, replaced to group joints of one family (`skin_12_joint` -> `skin_#_joint`).
_DIGITS = re.compile(r"\d+")


def _mirror_difference(a: Joint, b: Joint, options: MirrorOptions) -> str:
    if a.type != b.type:
        return f"type {a.type} vs {b.type}"
    length, angle = options.length_tolerance, options.angle_tolerance
    gap = max(abs(abs(x) - abs(y)) for x, y in zip(a.origin.xyz, b.origin.xyz))
    if gap > length:
        return (f"origin xyz ({_vector(a.origin.xyz)}) vs ({_vector(b.origin.xyz)}), "
                f"|difference| {gap:g} > {length:g}")
    rotation_gap = _mirrored_rotation_gap(a.origin.rpy, b.origin.rpy)
    if rotation_gap > angle:
        return (f"origin rpy ({_vector(a.origin.rpy)}) vs ({_vector(b.origin.rpy)}): no mirror "
                f"(with or without a half turn) maps one onto the other; closest "
                f"{rotation_gap:.3g} rad > {angle:g}")
    axis_a, axis_b = a.axis or (1.0, 0.0, 0.0), b.axis or (1.0, 0.0, 0.0)
    gap = max(abs(abs(x) - abs(y)) for x, y in zip(axis_a, axis_b))
    if gap > 1e-6:
        return f"axis ({_vector(axis_a)}) vs ({_vector(axis_b)}), |difference| {gap:g} > 1e-06"
    range_a, range_b = joint_range(a), joint_range(b)
    if range_a and range_b and range_a.bounded and range_b.bounded:
        tolerance = length if a.type == "prismatic" else angle
        same = max(abs(range_a.lower - range_b.lower), abs(range_a.upper - range_b.upper))
        mirrored = max(abs(range_a.lower + range_b.upper), abs(range_a.upper + range_b.lower))
        if min(same, mirrored) > tolerance:
            return (f"limits [{range_a.lower:g}, {range_a.upper:g}] vs "
                    f"[{range_b.lower:g}, {range_b.upper:g}]")
    return ""


#: The reflections a left/right mirror may use (through the yz, xz or xy plane, or none).
_REFLECTIONS = ((1.0, 1.0, 1.0), (-1.0, 1.0, 1.0), (1.0, -1.0, 1.0), (1.0, 1.0, -1.0))
#: Half turns about x, y, z (and none), as diagonal matrices.
_HALF_TURNS = ((1.0, 1.0, 1.0), (1.0, -1.0, -1.0), (-1.0, 1.0, -1.0), (-1.0, -1.0, 1.0))


def _mirrored_rotation_gap(rpy_a: Sequence[float], rpy_b: Sequence[float]) -> float:
    """The smallest rotation angle (rad) between frame b and frame a mirrored through a plane
    (P R P), possibly turned by a half turn about one of its own or the parent's axes.

    Angles are compared as rotations, so -4.71239 and 1.5708 are the same (modulo 2*pi)."""
    ra, rb = rpy_rotation(rpy_a), rpy_rotation(rpy_b)
    best = math.pi
    for p in _REFLECTIONS:
        mirrored = [[p[i] * ra[i][j] * p[j] for j in range(3)] for i in range(3)]
        for k in _HALF_TURNS:
            for candidate in ([[mirrored[i][j] * k[j] for j in range(3)] for i in range(3)],
                              [[k[i] * mirrored[i][j] for j in range(3)] for i in range(3)]):
                best = min(best, _rotation_angle(candidate, rb))
    return best


def _rotation_angle(r1: Sequence[Sequence[float]], r2: Sequence[Sequence[float]]) -> float:
    """Angle (rad) of the rotation r1^T r2."""
    trace = sum(r1[k][i] * r2[k][i] for i in range(3) for k in range(3))
    return math.acos(max(-1.0, min(1.0, (trace - 1.0) / 2.0)))


def _vector(values: Iterable[float]) -> str:
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
    options = ctx.options_as(MirrorMassOptions)
    for first, second in mirror_pairs(link.name for link in robot.links):
        a, b = robot.link(first), robot.link(second)
        if a is None or b is None:
            continue
        mass_a, mass_b = tree.link_mass(a), tree.link_mass(b)
        heavy = max(mass_a, mass_b)
        if heavy <= 0 or abs(mass_a - mass_b) <= options.relative_tolerance * heavy:
            continue
        where = (b.inertial.where if b.inertial else None) or b.where
        yield Finding(f"mirrored links '{first}' and '{second}' weigh {mass_a:g} kg and "
                      f"{mass_b:g} kg ({abs(mass_a - mass_b) / heavy:.0%} apart, tolerance "
                      f"{options.relative_tolerance:.0%})", where, f"link:{second}")


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
