"""Inertia rules (I1xx): is each declared `<inertial>` physically possible, and what do the
programs that load the model make of it?

Pure Python (no numpy): these rules run on every lint. The checks against meshes (I2xx) live
in `inertia_meshes.py`.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

from robotdesc.diagnostics import Finding, Severity
from robotdesc.inertia.links import (
    has_mass,
    is_dynamics_model,
    is_moving,
    link_element,
    mass_of,
    root_links,
)
from robotdesc.model.elements import Joint, Link, Robot
from robotdesc.model.tree import parent_joint_of
from robotdesc.rules.registry import RuleContext, rule
from robotdesc.source import Provenance
from robotdesc.spatial import (
    MAX_MATERIAL_DENSITY,
    minimum_trace,
    principal_moments,
    triangle_violation,
)

FAMILY = "inertia"

_CONSUMERS_MISSING = ("Gazebo's URDF-to-SDF conversion drops it together with its joint "
                      "and every link below it; PyBullet gives it a mass of 1 kg and "
                      "moments of 1 kg*m^2")


#: A tensor whose moments are below this fraction of the least possible (I105) is zero.
_NEGLIGIBLE = 1e-9


def _where(link: Link) -> Provenance | None:
    return link.inertial.where if link.inertial and link.inertial.where else link.where


@rule("I101", "moving-link-without-inertial", family=FAMILY, severity=Severity.ERROR,
      opt_in=True)
def moving_link_without_inertial(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a link moved by a joint (not fixed) that has no `<inertial>`, in a description
    meant for dynamics (one in which some moving link declares a mass).

    Opt-in since issue 29: on the blind part 1 of 5 was worth fixing (virtual wheels and
    finger-tip frames without inertia by design; docs/precision.md).

    A purely kinematic description, for a viewer or a planner, declares no masses and is
    not reported.

    Why is this bad?
    Simulators need every moving body's mass and inertia, and each fills the gap its own
    way: Gazebo's URDF-to-SDF conversion drops the link, its joint and every link below it
    (with only a console warning); PyBullet gives it a mass of 1 kg and moments of
    1 kg*m^2, far too heavy for a finger or a sensor; Pinocchio and Drake give it no mass,
    which makes the joint's motion singular when nothing heavier hangs below it.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/>
      <link name="arm">
        <inertial><mass value="1"/>
          <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
      </link>
      <link name="hand"/>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
      <joint name="wrist" type="continuous"><parent link="arm"/><child link="hand"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/>
      <link name="arm">
        <inertial><mass value="1"/>
          <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
      </link>
      <link name="hand">
        <inertial><mass value="0.2"/>
          <inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
      </link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
      <joint name="wrist" type="continuous"><parent link="arm"/><child link="hand"/></joint>
    </robot>
    ```
    """
    if not is_dynamics_model(robot):
        return
    parents = parent_joint_of(robot)
    for link in robot.links:
        if link.inertial is None and is_moving(link, parents):
            joint = parents[link.name]
            yield Finding(f"link '{link.name}' moves ({joint.type} joint '{joint.name}') but "
                          f"has no <inertial>: {_CONSUMERS_MISSING}", link.where,
                          f"link:{link.name}")


@rule("I102", "non-positive-mass", family=FAMILY, severity=Severity.ERROR)
def non_positive_mass(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a negative mass, or a mass of zero on a link moved by a joint.

    A zero mass on a link attached by a fixed joint (a tool frame, a sensor frame) is not
    reported: Gazebo lumps it into its parent, which has a mass. Two zero-mass links in a
    row on fixed joints are C103's (Gazebo lumps them into NaN); a pure frame is best
    written without `<inertial>`.

    Why is this bad?
    No body has a negative mass, and a moving body without mass makes the equations of
    motion singular. Gazebo's URDF-to-SDF conversion drops a link whose mass is not
    positive, together with its joint and the links below it.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/>
      <link name="arm">
        <inertial><mass value="0"/>
          <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
      </link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/>
      <link name="arm">
        <inertial><mass value="1.2"/>
          <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
      </link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
    </robot>
    ```
    """
    parents = parent_joint_of(robot)
    for link in robot.links:
        inertial = link.inertial
        if inertial is None or inertial.mass is None:
            continue
        if inertial.mass < 0:
            yield Finding(f"link '{link.name}' has a negative mass ({inertial.mass:g} kg)",
                          _where(link), link_element(link))
        elif inertial.mass == 0 and is_moving(link, parents):
            joint = parents[link.name]
            yield Finding(f"link '{link.name}' moves ({joint.type} joint '{joint.name}') but "
                          "its mass is 0 kg: its motion is singular, and Gazebo's URDF-to-SDF "
                          "conversion drops it with the links below it",
                          _where(link), link_element(link))


@rule("I103", "inertia-not-positive-definite", family=FAMILY, severity=Severity.ERROR)
def inertia_not_positive_definite(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds an inertia tensor with a negative principal moment, or, on a link with mass,
    one that is not positive definite (a zero tensor, or zero about some axis), moving or
    not: a root link or a fixed link too.

    A point mass (zero tensor) on a link attached by a fixed joint is allowed: it is lumped
    into its parent's body. A singular tensor that is not zero (rank 1 or 2, a rod or a
    plate with no thickness) is reported on every link: MuJoCo refuses such a body and
    Drake warns, even on a root link.

    Why is this bad?
    A rigid body's inertia tensor is positive definite. Physics engines invert it: a zero
    or negative moment gives infinite or reversed angular acceleration, and engines either
    refuse the model (Pinocchio, Drake), clamp it silently (Gazebo/ODE, MuJoCo's
    `balanceinertia`) or blow up.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/>
      <link name="arm">
        <inertial><mass value="1"/>
          <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>
      </link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/>
      <link name="arm">
        <inertial><mass value="1"/>
          <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.002"/></inertial>
      </link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
    </robot>
    ```
    """
    parents = parent_joint_of(robot)
    for link in robot.links:
        inertial = link.inertial
        if inertial is None or inertial.inertia is None or not has_mass(link):
            continue
        moments = principal_moments(inertial.inertia.matrix())
        scale = max(abs(m) for m in moments)
        where = inertial.inertia.where or _where(link)
        joint = parents.get(link.name)
        lumped = joint is not None and joint.type == "fixed"
        role = ("moves" if is_moving(link, parents) else "is fixed to its parent" if lumped
                else "is a root link")
        if scale <= _NEGLIGIBLE * minimum_trace(mass_of(link)):
            if not lumped:
                shown = "is zero" if scale == 0 else f"is zero (largest moment {scale:.3g})"
                yield Finding(f"link '{link.name}' {role} and has a mass of "
                              f"{inertial.mass:g} kg, but its inertia tensor {shown}", where,
                              link_element(link))
        elif moments[0] < -1e-9 * scale:
            yield Finding(f"link '{link.name}': the inertia tensor has a negative principal "
                          f"moment ({_moments(moments)} kg*m^2); no body has one",
                          where, link_element(link))
        elif moments[0] <= 1e-12 * scale:
            yield Finding(f"link '{link.name}' {role} and has a mass of {inertial.mass:g} kg, "
                          f"but its inertia tensor is singular (principal moments "
                          f"{_moments(moments)} kg*m^2): MuJoCo refuses the body, Drake warns",
                          where, link_element(link))


@dataclass(frozen=True)
class TriangleOptions:
    """Options of I104.

    Attributes:
        tolerance: relative slack (of the largest principal moment) before a violation is
            reported; covers values rounded when they were written.
    """

    tolerance: float = 1e-3


@rule("I104", "inertia-triangle-inequality", family=FAMILY, severity=Severity.ERROR,
      options=TriangleOptions)
def inertia_triangle_inequality(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds an inertia tensor whose principal moments violate the triangle inequality:
    the largest is more than the sum of the other two.

    Why is this bad?
    For any real body each principal moment is at most the sum of the other two (equality
    only for a flat plate). A tensor that breaks this describes no body at all; Gazebo's
    DART and Bullet reject or misbehave with it, and MuJoCo refuses to load it. Often a
    value was mistyped or copied from another link.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/>
      <link name="arm">
        <inertial><mass value="1"/>
          <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.05"/></inertial>
      </link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/>
      <link name="arm">
        <inertial><mass value="1"/>
          <inertia ixx="0.03" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.05"/></inertial>
      </link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
    </robot>
    ```
    """
    tolerance = ctx.options_as(TriangleOptions).tolerance
    for link in robot.links:
        inertial = link.inertial
        if inertial is None or inertial.inertia is None or not has_mass(link):
            continue
        moments = principal_moments(inertial.inertia.matrix())
        if moments[0] <= 0:
            continue  # I103's finding
        excess = triangle_violation(moments)
        if excess > tolerance * moments[2]:
            yield Finding(f"link '{link.name}': principal moments {_moments(moments)} kg*m^2 "
                          f"break the triangle inequality: {moments[0]:.6g} + {moments[1]:.6g} "
                          f"= {moments[0] + moments[1]:.6g} < {moments[2]:.6g}, short by "
                          f"{excess:.3g} kg*m^2 ({100 * excess / moments[2]:.3g}% of the "
                          "largest)", inertial.inertia.where or _where(link), link_element(link))


#: A link on a fixed joint lighter than this (kg) is a small fixed part (a 5 g camera or
#: IMU board): Gazebo and the dynamics libraries lump it into its parent, where its inertia
#: is lost in the parent's, so I105 does not judge it.
SMALL_FIXED_MASS = 0.1


def _small_fixed_part(link: Link, parents: dict[str, Joint]) -> bool:
    joint = parents.get(link.name)
    return (joint is not None and joint.type == "fixed"
            and mass_of(link) < SMALL_FIXED_MASS)


@dataclass(frozen=True)
class TinyInertiaOptions:
    """Options of I105.

    Attributes:
        max_density: the densest material assumed possible (kg/m^3); osmium by default.
    """

    max_density: float = MAX_MATERIAL_DENSITY


@rule("I105", "implausibly-small-inertia", family=FAMILY, severity=Severity.WARNING,
      options=TinyInertiaOptions, opt_in=True)
def implausibly_small_inertia(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds an inertia too small for the link's mass: no solid of that mass, even one made
    entirely of the densest metal, has moments that small.

    Opt-in since issue 29: on the blind part 1 of 5 was worth fixing (marker links of a
    docking station; docs/precision.md).

    The bound: the sum of the principal moments is smallest for a uniform ball, 6/5 m R^2,
    and the ball is smallest at the highest density (osmium, 22 600 kg/m^3). A link under
    100 g on a fixed joint (a sensor board) is not judged: it is lumped into its parent,
    whose inertia hides its own.

    Why is this bad?
    Placeholder values such as `ixx="1e-6"` on a 1 kg link make the link spin up almost
    without torque; simulators need tiny time steps or become unstable, and controllers
    tuned on the model misjudge the real robot.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/>
      <link name="arm">
        <inertial><mass value="2"/>
          <inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/></inertial>
      </link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/>
      <link name="arm">
        <inertial><mass value="2"/>
          <inertia ixx="0.017" ixy="0" ixz="0" iyy="0.017" iyz="0" izz="0.002"/></inertial>
      </link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
    </robot>
    ```
    """
    density = ctx.options_as(TinyInertiaOptions).max_density
    parents = parent_joint_of(robot)
    for link in robot.links:
        inertial = link.inertial
        if inertial is None or inertial.inertia is None or not has_mass(link):
            continue
        if _small_fixed_part(link, parents):
            continue
        moments = principal_moments(inertial.inertia.matrix())
        if moments[0] <= 0:
            continue  # I103's finding
        trace = sum(moments)
        mass = mass_of(link)
        bound = minimum_trace(mass, density)
        if trace < bound:
            radius = math.sqrt(trace / (1.2 * mass))
            yield Finding(f"link '{link.name}': moments {_moments(moments)} kg*m^2 are too "
                          f"small for {inertial.mass:g} kg: their sum {trace:.3g} is below "
                          f"{bound:.3g}, the least any solid of that mass can have (a ball of "
                          f"{density:g} kg/m^3); it would be a ball of radius "
                          f"{radius * 1000:.3g} mm", inertial.inertia.where or _where(link),
                          link_element(link))


@dataclass(frozen=True)
class RootInertiaOptions:
    """Options of I106.

    Attributes:
        min_share: report a root link whose mass is more than this share of the robot's
            total declared mass (0: every root link with a mass).
    """

    min_share: float = 0.5


@rule("I106", "root-link-inertia", family=FAMILY, severity=Severity.INFO,
      options=RootInertiaOptions, opt_in=True)
def root_link_inertia(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a root link that carries most of the robot's mass (over half, by default), in a
    description meant for dynamics.

    Opt-in since issue 29 (info): on the blind part 0 of 3 were worth fixing (a mobile
    base's and standalone grippers' roots; docs/precision.md).

    Why is this bad?
    KDL (kdl_parser: robot_state_publisher, MoveIt's KDL solvers, many controllers) cannot
    represent the root link's inertia: it warns on every start and leaves the mass out of
    its dynamics. For a fixed-base arm whose base is a small part of its mass that is
    harmless (hence the default threshold); for a mobile or legged robot whose body is most
    of its mass, KDL's total mass and centre of mass are then far off. The usual fix is a massless root link
    (`base_footprint`, `base_link`) joined to the body by a fixed joint.

    Example
    ```xml
    <robot name="rover">
      <link name="body">
        <inertial><mass value="10"/>
          <inertia ixx="0.2" ixy="0" ixz="0" iyy="0.3" iyz="0" izz="0.4"/></inertial>
      </link>
      <link name="wheel">
        <inertial><mass value="0.5"/>
          <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.002"/></inertial>
      </link>
      <joint name="axle" type="continuous"><parent link="body"/><child link="wheel"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="rover">
      <link name="base_link"/>
      <link name="body">
        <inertial><mass value="10"/>
          <inertia ixx="0.2" ixy="0" ixz="0" iyy="0.3" iyz="0" izz="0.4"/></inertial>
      </link>
      <link name="wheel">
        <inertial><mass value="0.5"/>
          <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.002"/></inertial>
      </link>
      <joint name="base_joint" type="fixed"><parent link="base_link"/><child link="body"/></joint>
      <joint name="axle" type="continuous"><parent link="body"/><child link="wheel"/></joint>
    </robot>
    ```
    """
    share = ctx.options_as(RootInertiaOptions).min_share
    if not is_dynamics_model(robot):
        return
    total = sum(mass_of(link) for link in robot.links)
    for link in root_links(robot):
        if has_mass(link) and mass_of(link) > share * total:
            yield Finding(f"root link '{link.name}' has a mass of {mass_of(link):g} kg, "
                          "which KDL (robot_state_publisher, MoveIt's KDL solvers) ignores: add "
                          "a massless root link joined to it by a fixed joint",
                          _where(link), link_element(link))


@rule("I107", "fixed-link-without-inertial", family=FAMILY, severity=Severity.WARNING,
      opt_in=True)
def fixed_link_without_inertial(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a link attached by a fixed joint without an `<inertial>`, in a description
    meant for dynamics.

    Why is this bad?
    Consumers disagree about such a link. Gazebo lumps it into its parent (nothing added),
    but PyBullet, unless told to merge fixed links, gives every link without `<inertial>`
    a mass of 1 kg and moments of 1 kg*m^2: a tool frame or a camera frame becomes a
    phantom kilogram at the end of the arm.

    The fix is on PyBullet's side (`flags=p.URDF_MERGE_FIXED_LINKS`), or the real mass of
    what the frame carries. Not a zero-mass `<inertial>`: Gazebo lumps a chain of zero-mass
    links into a NaN centre of mass (C103), and drops a massless body kept by
    `disableFixedJointLumping` (C101).

    Off by default (most descriptions keep sensor and tool frames without `<inertial>`):
    turn it on with `--select I107` or in the config when the model is for PyBullet. C104
    reports every link PyBullet weighs at 1 kg, moving or fixed.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/>
      <link name="arm">
        <inertial><mass value="1"/>
          <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
      </link>
      <link name="camera"/>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
      <joint name="camera_mount" type="fixed"><parent link="arm"/><child link="camera"/></joint>
    </robot>
    ```

    Use instead (the camera's real mass; or load with URDF_MERGE_FIXED_LINKS):
    ```xml
    <robot name="arm">
      <link name="base"/>
      <link name="arm">
        <inertial><mass value="1"/>
          <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
      </link>
      <link name="camera">
        <inertial><mass value="0.07"/>
          <inertia ixx="4e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="4e-5"/></inertial>
      </link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
      <joint name="camera_mount" type="fixed"><parent link="arm"/><child link="camera"/></joint>
    </robot>
    ```
    """
    if not is_dynamics_model(robot):
        return
    parents = parent_joint_of(robot)
    for link in robot.links:
        joint = parents.get(link.name)
        if link.inertial is None and joint is not None and joint.type == "fixed":
            yield Finding(f"link '{link.name}' (fixed joint '{joint.name}') has no <inertial>: "
                          "PyBullet gives it 1 kg and moments of 1 kg*m^2 unless fixed links "
                          "are merged (URDF_MERGE_FIXED_LINKS)",
                          link.where, f"link:{link.name}")


def _moments(moments: Iterable[float]) -> str:
    return "(" + ", ".join(f"{m:.6g}" for m in moments) + ")"
