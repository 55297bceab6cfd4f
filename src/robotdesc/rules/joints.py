"""Joint rules (J1xx): types, limits and axes."""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass

from robotdesc.diagnostics import Finding, Severity, ValueChange
from robotdesc.model.elements import Joint, Robot
from robotdesc.model.tree import LIMITED_TYPES, SCALAR_TYPES
from robotdesc.rules.registry import RuleContext, rule

FAMILY = "joints"

#: The joint types URDF defines.
JOINT_TYPES = frozenset({"revolute", "continuous", "prismatic", "fixed", "floating", "planar"})
#: Joint types whose `<limit>` is required: `tree.LIMITED_TYPES`.
#: Joint types that read `<limit effort velocity>`: the one-variable ones.
ACTUATED_TYPES = SCALAR_TYPES


def is_frozen(joint: Joint) -> bool:
    """Whether a revolute or prismatic joint is frozen on purpose: its `<limit>` writes
    `lower` and `upper` and they are equal (RotorS keeps sensor links apart this way, so that
    Gazebo does not lump them). Its velocity and effort limits mean nothing."""
    limit = joint.limit
    return (joint.type in LIMITED_TYPES and limit is not None and limit.lower is not None
            and limit.upper is not None and limit.lower == limit.upper)
#: Joint types whose `<axis>` matters (planar: the plane's normal).
AXIS_TYPES = frozenset({"revolute", "continuous", "prismatic", "planar"})


@rule("J101", "invalid-joint-type", family=FAMILY, severity=Severity.ERROR)
def invalid_joint_type(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a joint whose `type` is missing or not one of URDF's six joint types:
    revolute, continuous, prismatic, fixed, floating, planar.

    Why is this bad?
    urdfdom rejects the file ("Joint has no known type"). Types from other formats
    (`spherical`, `ball`, `hinge`, `slider`) are not URDF.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="hinge"><parent link="base"/><child link="arm"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
    </robot>
    ```
    """
    for joint in robot.joints:
        if joint.type not in JOINT_TYPES:
            what = f"type '{joint.type}' is not a URDF joint type" if joint.type else "has no type"
            yield Finding(f"joint '{joint.name}' {what} (expected one of: "
                          + ", ".join(sorted(JOINT_TYPES)) + ")",
                          joint.where, f"joint:{joint.name}")


@rule("J102", "missing-joint-limit", family=FAMILY, severity=Severity.ERROR)
def missing_joint_limit(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a revolute or prismatic joint without a `<limit>` element.

    Why is this bad?
    URDF requires `<limit>` (with `effort` and `velocity`) on revolute and prismatic
    joints; urdfdom rejects the joint, and planners have no range to respect.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
      </joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1.57" upper="1.57" effort="30" velocity="2"/>
      </joint>
    </robot>
    ```
    """
    for joint in robot.joints:
        if joint.type in LIMITED_TYPES and joint.limit is None:
            yield Finding(f"{joint.type} joint '{joint.name}' has no <limit>",
                          joint.where, f"joint:{joint.name}")


@rule("J103", "limit-lower-above-upper", family=FAMILY, severity=Severity.ERROR)
def limit_lower_above_upper(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a revolute or prismatic joint whose lower limit is above its upper limit.

    Why is this bad?
    The joint has no valid position. Planners and controllers either reject the model or
    clamp every command to a meaningless value. Usually the two values are swapped, or
    one has the wrong sign.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="elbow" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
        <limit lower="2.0" upper="-0.5" effort="30" velocity="2"/>
      </joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="elbow" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
        <limit lower="-0.5" upper="2.0" effort="30" velocity="2"/>
      </joint>
    </robot>
    ```
    """
    for joint in robot.joints:
        limit = joint.limit
        if joint.type not in LIMITED_TYPES or limit is None:
            continue
        lower = 0.0 if limit.lower is None else limit.lower
        upper = 0.0 if limit.upper is None else limit.upper
        if lower > upper:
            both = limit.lower is not None and limit.upper is not None
            swap = (ValueChange(f"joint:{joint.name}/limit", "lower", repr(upper)),
                    ValueChange(f"joint:{joint.name}/limit", "upper", repr(lower)))
            yield Finding(f"joint '{joint.name}' lower limit {lower:g} is above its upper "
                          f"limit {upper:g}", limit.where or joint.where, f"joint:{joint.name}",
                          changes=swap if both else ())


@rule("J104", "non-positive-effort", family=FAMILY, severity=Severity.WARNING)
def non_positive_effort(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a revolute, continuous or prismatic joint whose `<limit effort>` is negative.

    A zero effort is the ROS-Industrial convention for "unknown"; J110 reports it (info).

    Why is this bad?
    `effort` is the largest force (N) or torque (N*m) the joint may exert; a negative value
    is meaningless, and Gazebo and ros2_control clamp every command to it.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="-30" velocity="2"/>
      </joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="30" velocity="2"/>
      </joint>
    </robot>
    ```
    """
    for joint in robot.joints:
        limit = joint.limit
        if joint.type in ACTUATED_TYPES and limit is not None and limit.effort is not None \
                and limit.effort < 0:
            yield Finding(f"joint '{joint.name}' effort limit is {limit.effort:g} "
                          "(must be positive)", limit.where or joint.where,
                          f"joint:{joint.name}")


@rule("J110", "unknown-effort-limit", family=FAMILY, severity=Severity.INFO, opt_in=True)
def unknown_effort_limit(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a revolute, continuous or prismatic joint whose `<limit effort>` is 0, the
    ROS-Industrial convention for "unknown". A frozen joint (`lower == upper`) is skipped.

    Opt-in: the convention is deliberate (no manufacturer torque limit published), and the
    blind sample of issue 29 judged every finding noise on packages that follow it.

    Why is this bad?
    It is a convention, not an error: ROS-Industrial descriptions write `effort="0"` when the
    manufacturer publishes no torque limit. But every consumer reads it as a limit: Gazebo and
    ros2_control clamp effort commands to 0, so an effort-controlled joint never moves.
    Write the real limit when the description is used for simulation or effort control.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="0" velocity="2"/>
      </joint>
    </robot>
    ```

    Use instead (the manufacturer's limit, in N*m):
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="30" velocity="2"/>
      </joint>
    </robot>
    ```
    """
    for joint in robot.joints:
        limit = joint.limit
        if joint.type in ACTUATED_TYPES and limit is not None and limit.effort == 0 \
                and not is_frozen(joint):
            yield Finding(f"joint '{joint.name}' effort limit is 0, the ROS-Industrial "
                          "\"unknown\": Gazebo and ros2_control clamp effort commands to 0",
                          limit.where or joint.where, f"joint:{joint.name}")


@rule("J105", "non-positive-velocity", family=FAMILY, severity=Severity.WARNING)
def non_positive_velocity(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a revolute, continuous or prismatic joint whose `<limit velocity>` is zero or
    negative. A frozen joint (`lower == upper`, both written) is skipped: it is not meant
    to move (RotorS freezes its sensor joints so that Gazebo keeps the links apart). So is a
    joint whose effort is 0 too: the ROS-Industrial convention for limits not given (J110,
    opt-in, reports it), used on passive joints such as a robot vacuum's wheel drop.

    Why is this bad?
    `velocity` is the largest speed (rad/s or m/s) of the joint. With 0, velocity-limited
    controllers and planners (MoveIt time parameterization) cannot move the joint; a
    negative value is meaningless.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="30" velocity="0"/>
      </joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="30" velocity="2"/>
      </joint>
    </robot>
    ```
    """
    for joint in robot.joints:
        limit = joint.limit
        if joint.type in ACTUATED_TYPES and limit is not None and limit.velocity is not None \
                and limit.velocity <= 0 and not is_frozen(joint) and limit.effort != 0:
            yield Finding(f"joint '{joint.name}' velocity limit is {limit.velocity:g} "
                          "(must be positive)", limit.where or joint.where,
                          f"joint:{joint.name}")


@rule("J106", "zero-joint-axis", family=FAMILY, severity=Severity.ERROR)
def zero_joint_axis(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a moving joint (revolute, continuous, prismatic, planar) whose `<axis xyz>`
    is the zero vector.

    Why is this bad?
    A zero axis has no direction: normalising it divides by zero, so kinematics libraries
    produce NaNs or reject the model, and the joint cannot move.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="wheel"/>
      <joint name="wheel_joint" type="continuous">
        <parent link="base"/><child link="wheel"/><axis xyz="0 0 0"/>
      </joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="wheel"/>
      <joint name="wheel_joint" type="continuous">
        <parent link="base"/><child link="wheel"/><axis xyz="0 1 0"/>
      </joint>
    </robot>
    ```
    """
    for joint in robot.joints:
        if joint.type in AXIS_TYPES and joint.axis is not None and not any(joint.axis):
            yield Finding(f"{joint.type} joint '{joint.name}' has a zero axis",
                          joint.axis_where or joint.where, f"joint:{joint.name}")


@dataclass(frozen=True)
class AxisOptions:
    """Options of `axis-not-normalized`.

    Attributes:
        tolerance: largest accepted difference between the axis length and 1.
    """

    tolerance: float = 1e-3


@rule("J107", "axis-not-normalized", family=FAMILY, severity=Severity.WARNING,
      options=AxisOptions)
def axis_not_normalized(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a moving joint whose `<axis xyz>` is not a unit vector.

    Why is this bad?
    URDF asks for a unit axis. Some consumers normalise it, others use it as written and
    scale the joint's motion by its length (a prismatic joint moving 2 m per commanded
    metre), so the same file behaves differently in different tools.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="tilt" type="continuous">
        <parent link="base"/><child link="arm"/><axis xyz="1 1 0"/>
      </joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="tilt" type="continuous">
        <parent link="base"/><child link="arm"/><axis xyz="0.707107 0.707107 0"/>
      </joint>
    </robot>
    ```
    """
    tolerance = ctx.options_as(AxisOptions).tolerance
    for joint in robot.joints:
        if joint.type not in AXIS_TYPES or joint.axis is None or not any(joint.axis):
            continue
        length = math.sqrt(sum(c * c for c in joint.axis))
        if abs(length - 1.0) > tolerance:
            unit = " ".join(f"{c / length:.6g}" for c in joint.axis)
            yield Finding(f"joint '{joint.name}' axis has length {length:.6g}, not 1 "
                          f"(normalized: {unit})", joint.axis_where or joint.where,
                          f"joint:{joint.name}", fix=f'<axis xyz="{unit}"/>',
                          changes=(ValueChange(f"joint:{joint.name}/axis", "xyz", unit),))


#: A range at least this wide (rad, with rounding slack) on a continuous joint limits nothing.
FULL_TURN = 2 * math.pi - 1e-6


@rule("J108", "continuous-joint-with-position-limits", family=FAMILY,
      severity=Severity.WARNING)
def continuous_joint_with_position_limits(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a continuous joint whose `<limit>` sets a non-zero `lower` or `upper` spanning
    less than a full turn: a range the author meant to enforce, which consumers ignore.
    Limits of a full turn or more (`-6.28 .. 6.28`, Kinova's convention for an endless
    joint) restrict nothing and are not reported.

    Why is this bad?
    A continuous joint has no position limits; consumers ignore `lower`/`upper` on it. If
    the range matters, the joint should be `revolute`; if not, the values mislead readers.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="wheel"/>
      <joint name="wheel_joint" type="continuous">
        <parent link="base"/><child link="wheel"/><axis xyz="0 1 0"/>
        <limit lower="-3.14" upper="3.14" effort="10" velocity="5"/>
      </joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="wheel"/>
      <joint name="wheel_joint" type="continuous">
        <parent link="base"/><child link="wheel"/><axis xyz="0 1 0"/>
        <limit effort="10" velocity="5"/>
      </joint>
    </robot>
    ```
    """
    for joint in robot.joints:
        limit = joint.limit
        if joint.type != "continuous" or limit is None:
            continue
        span = (limit.upper or 0.0) - (limit.lower or 0.0)
        if span >= FULL_TURN:
            continue
        if (limit.lower or 0.0) != 0.0 or (limit.upper or 0.0) != 0.0:
            lower = "unset" if limit.lower is None else f"{limit.lower:g}"
            upper = "unset" if limit.upper is None else f"{limit.upper:g}"
            yield Finding(f"continuous joint '{joint.name}' has position limits "
                          f"lower={lower} upper={upper} that consumers ignore",
                          limit.where or joint.where, f"joint:{joint.name}")
