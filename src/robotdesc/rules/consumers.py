"""The consumers' view (C1xx): what the programs that load a URDF make of it.

Gazebo loads a URDF through libsdformat's URDF->SDF conversion, which first lumps every link
on a fixed joint into its parent (unless the joint's `<gazebo>` block asks to preserve it) and
then drops every body without mass together with everything below it. PyBullet and MuJoCo
fill gaps their own way; yourdfpy (`robotdesc.to_yourdfpy`) refuses a few shapes and moves a
few joints differently. Pure checks of the model: no meshes, no Pinocchio.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from robotdesc.diagnostics import Finding, Severity
from robotdesc.inertia.links import is_dynamics_model
from robotdesc.model import tree
from robotdesc.model.elements import Capsule, Joint, Link, Robot
from robotdesc.rules.registry import RuleContext, rule

FAMILY = "consumers"

#: `<gazebo reference="JOINT">` tags that keep a fixed joint from being lumped.
_PRESERVE_TAGS = frozenset({"disableFixedJointLumping", "preserveFixedJoint"})
#: Link names that Gazebo's conversion treats as the world, not a body.
_WORLD = "world"


@dataclass(frozen=True)
class GazeboBody:
    """A body of the converted model: links lumped by fixed joints.

    Attributes:
        head: the link that heads it (its joint to the parent body is not lumped).
        links: every link lumped into it, head first.
        mass: the sum of their declared masses (kg); links without `<inertial>` add 0.
        joint: the joint to the parent body (None for a root).
    """

    head: str
    links: tuple[str, ...]
    mass: float
    joint: Joint | None


def _preserved(robot: Robot) -> set[str]:
    """Fixed joints whose `<gazebo>` block keeps them from being lumped."""
    return {block.reference for block in robot.gazebo
            if block.reference and _PRESERVE_TAGS & set(block.tags)}


def gazebo_bodies(robot: Robot) -> dict[str, GazeboBody]:
    """Head link name -> the body libsdformat makes of it (fixed joints lumped)."""
    parents = tree.parent_joint_of(robot)
    head = tree.body_of(robot, keep=_preserved(robot))
    members: dict[str, list[str]] = {}
    for link in robot.links:
        members.setdefault(head[link.name], []).append(link.name)
    bodies = {}
    for name, links in members.items():
        mass = sum(tree.link_mass(robot.link(n)) for n in links)
        ordered = [name] + [n for n in links if n != name]
        bodies[name] = GazeboBody(name, tuple(ordered), mass, parents.get(name))
    return bodies


def _names(links: list[str], limit: int = 8) -> str:
    shown = ", ".join(f"'{n}'" for n in links[:limit])
    return shown + (f" and {len(links) - limit} more" if len(links) > limit else "")


def _moving_children(robot: Robot, body: GazeboBody) -> list[Joint]:
    inside = set(body.links)
    return [j for j in robot.joints if j.parent in inside and j.child not in inside]


@rule("C101", "gazebo-drops-massless-body", family=FAMILY, severity=Severity.ERROR)
def gazebo_drops_massless_body(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a link that Gazebo's URDF->SDF conversion drops together with everything below
    it: after links on fixed joints are lumped into their parents, a body without mass (no
    `<inertial>`, or a mass of 0) hanging on a moving joint, with bodies below it.

    Only descriptions meant for dynamics are checked (some moving link declares a mass).
    The message names every link lost. A massless leaf link is I101's.

    Why is this bad?
    libsdformat skips the massless body with a debug-level message, and with it every joint
    and link below it: a whole gripper, a hand's fingers, vanish from the simulation while the
    URDF looks fine in RViz and MoveIt.

    Example
    ```xml
    <robot name="arm">
      <link name="base"><inertial><mass value="2"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <link name="gripper_base"/>
      <link name="finger"><inertial><mass value="0.05"/>
        <inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial></link>
      <joint name="wrist" type="revolute"><parent link="base"/><child link="gripper_base"/>
        <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="5" velocity="2"/></joint>
      <joint name="finger_joint" type="prismatic"><parent link="gripper_base"/><child link="finger"/>
        <axis xyz="1 0 0"/><limit lower="0" upper="0.04" effort="20" velocity="0.1"/></joint>
    </robot>
    ```

    Use instead (the gripper base's real mass and inertia):
    ```xml
    <robot name="arm">
      <link name="base"><inertial><mass value="2"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <link name="gripper_base"><inertial><mass value="0.4"/>
        <inertia ixx="4e-4" ixy="0" ixz="0" iyy="4e-4" iyz="0" izz="3e-4"/></inertial></link>
      <link name="finger"><inertial><mass value="0.05"/>
        <inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial></link>
      <joint name="wrist" type="revolute"><parent link="base"/><child link="gripper_base"/>
        <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="5" velocity="2"/></joint>
      <joint name="finger_joint" type="prismatic"><parent link="gripper_base"/><child link="finger"/>
        <axis xyz="1 0 0"/><limit lower="0" upper="0.04" effort="20" velocity="0.1"/></joint>
    </robot>
    ```
    """
    if not is_dynamics_model(robot):
        return
    for body in gazebo_bodies(robot).values():
        joint = body.joint
        if joint is None or body.mass > 0:
            continue  # a body on a fixed joint exists only when the joint is preserved
        if not _moving_children(robot, body):
            continue
        lost = tree.subtree(robot, body.head)
        link = robot.link(body.head)
        yield Finding(f"link '{body.head}' ({joint.type} joint '{joint.name}') has no mass, so "
                      f"Gazebo's URDF->SDF conversion drops it and everything below it: "
                      f"{len(lost)} links lost ({_names(lost)}); give it an <inertial> with "
                      "its real mass", link.where if link else joint.where,
                      f"link:{body.head}")


@rule("C102", "gazebo-drops-model", family=FAMILY, severity=Severity.ERROR)
def gazebo_drops_model(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a root link without mass on a moving joint: Gazebo's URDF->SDF conversion drops
    the root and everything below it, so the model has no links at all.

    A root named `world` is Gazebo's world (the robot is fixed to it) and is not reported; a
    massless root on a fixed joint is lumped into its child and is fine.

    Why is this bad?
    Gazebo refuses to spawn the model, or spawns nothing, with only a debug-level message
    ("has no inertia, not modeled in sdf").

    Example
    ```xml
    <robot name="arm">
      <link name="base_link"/>
      <link name="arm"><inertial><mass value="1"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <joint name="shoulder" type="continuous"><parent link="base_link"/><child link="arm"/>
        <axis xyz="0 0 1"/></joint>
    </robot>
    ```

    Use instead (a massless root on a fixed joint is lumped; or give the base its mass):
    ```xml
    <robot name="arm">
      <link name="base_footprint"/>
      <link name="base_link"><inertial><mass value="4"/>
        <inertia ixx="0.05" ixy="0" ixz="0" iyy="0.05" iyz="0" izz="0.05"/></inertial></link>
      <link name="arm"><inertial><mass value="1"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <joint name="base_joint" type="fixed"><parent link="base_footprint"/><child link="base_link"/></joint>
      <joint name="shoulder" type="continuous"><parent link="base_link"/><child link="arm"/>
        <axis xyz="0 0 1"/></joint>
    </robot>
    ```
    """
    if not is_dynamics_model(robot):
        return
    for body in gazebo_bodies(robot).values():
        if body.joint is not None or body.mass > 0 or body.head == _WORLD:
            continue
        moving = [j for j in _moving_children(robot, body) if j.type != "fixed"]
        if not moving:
            continue
        link = robot.link(body.head)
        lost = tree.subtree(robot, body.head)
        yield Finding(f"root link '{body.head}' has no mass and moving joint(s) "
                      f"({_names([j.name for j in moving], 4)}): Gazebo's URDF->SDF "
                      f"conversion drops it and all {len(lost)} links below it, leaving an "
                      "empty model; give it an <inertial>, or put a massless root on a "
                      "fixed joint above it", link.where if link else robot.where,
                      f"link:{body.head}")


@rule("C103", "gazebo-lumps-zero-masses", family=FAMILY, severity=Severity.ERROR)
def gazebo_lumps_zero_masses(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a link with an `<inertial>` of mass 0 on a fixed joint below another link with
    an `<inertial>` of mass 0: a chain of zero-mass frames.

    Why is this bad?
    Gazebo's URDF->SDF conversion lumps the child's inertial into its parent's, dividing by
    the sum of their masses to place the centre of mass: 0 / 0 gives NaN, the NaN spreads to
    the body the chain is lumped into, and Gazebo (classic) fails to load the whole model.
    A pure frame needs no `<inertial>` at all (Gazebo lumps it, adding nothing).

    Example
    ```xml
    <robot name="head">
      <link name="head"><inertial><mass value="1"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <link name="camera_link"><inertial><mass value="0"/>
        <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
      <link name="camera_optical_frame"><inertial><mass value="0"/>
        <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
      <joint name="camera_joint" type="fixed"><parent link="head"/><child link="camera_link"/></joint>
      <joint name="optical_joint" type="fixed"><parent link="camera_link"/><child link="camera_optical_frame"/></joint>
    </robot>
    ```

    Use instead (frames without `<inertial>`):
    ```xml
    <robot name="head">
      <link name="head"><inertial><mass value="1"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <link name="camera_link"/>
      <link name="camera_optical_frame"/>
      <joint name="camera_joint" type="fixed"><parent link="head"/><child link="camera_link"/></joint>
      <joint name="optical_joint" type="fixed"><parent link="camera_link"/><child link="camera_optical_frame"/></joint>
    </robot>
    ```
    """
    preserved = _preserved(robot)
    for joint in robot.joints:
        if joint.type != "fixed" or joint.name in preserved:
            continue
        parent, child = robot.link(joint.parent), robot.link(joint.child)
        if child is not None and child.inertial is not None and _zero_inertial(parent) \
                and _zero_inertial(child):
            yield Finding(f"links '{joint.parent}' and '{joint.child}' (fixed joint "
                          f"'{joint.name}') both declare a mass of 0: Gazebo's URDF->SDF "
                          "conversion lumps them into a NaN centre of mass (0 / 0) and fails "
                          "to load the model; remove the <inertial> of pure frames",
                          child.inertial.where or child.where, f"link:{joint.child}/inertial")


def _zero_inertial(link: Link | None) -> bool:
    return link is not None and link.inertial is not None and link.inertial.mass == 0


@rule("C104", "pybullet-default-inertia", family=FAMILY, severity=Severity.INFO, opt_in=True)
def pybullet_default_inertia(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a link without `<inertial>` in a description meant for dynamics: PyBullet gives
    it a mass of 1 kg and moments of 1 kg*m^2.

    Off by default (a concern only for PyBullet users): turn it on with `--select C104`. A
    frame on a fixed joint is harmless when the model is loaded with
    `flags=p.URDF_MERGE_FIXED_LINKS`; otherwise give it the real mass of what it carries.
    A zero-mass `<inertial>` is not the fix: Gazebo drops a massless body on a moving joint
    (C101) and lumps chains of them into NaN (C103).

    Why is this bad?
    A tool frame or a camera frame becomes a phantom kilogram at the end of the arm.

    Example
    ```xml
    <robot name="arm">
      <link name="arm"><inertial><mass value="1"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <link name="wrist"/>
      <link name="hand"><inertial><mass value="0.3"/>
        <inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>
      <joint name="wrist_joint" type="continuous"><parent link="arm"/><child link="wrist"/></joint>
      <joint name="hand_joint" type="continuous"><parent link="wrist"/><child link="hand"/></joint>
    </robot>
    ```

    Use instead (the wrist's real mass):
    ```xml
    <robot name="arm">
      <link name="arm"><inertial><mass value="1"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <link name="wrist"><inertial><mass value="0.2"/>
        <inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>
      <link name="hand"><inertial><mass value="0.3"/>
        <inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>
      <joint name="wrist_joint" type="continuous"><parent link="arm"/><child link="wrist"/></joint>
      <joint name="hand_joint" type="continuous"><parent link="wrist"/><child link="hand"/></joint>
    </robot>
    ```
    """
    if not is_dynamics_model(robot):
        return
    parents = tree.parent_joint_of(robot)
    for link in robot.links:
        if link.inertial is None and link.name in parents:
            joint = parents[link.name]
            how = ("unless the model is loaded with URDF_MERGE_FIXED_LINKS"
                   if joint.type == "fixed" else "and simulates it as such")
            yield Finding(f"link '{link.name}' has no <inertial>: PyBullet gives it 1 kg and "
                          f"moments of 1 kg*m^2 {how}", link.where, f"link:{link.name}")


@rule("C105", "mujoco-ignores-mimic", family=FAMILY, severity=Severity.INFO, opt_in=True)
def mujoco_ignores_mimic(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds mimic joints, which MuJoCo's URDF import drops: the joints move independently.

    Off by default (a concern only for MuJoCo users): turn it on with `--select C105`. In
    MuJoCo, couple the joints with an `<equality><joint joint1=... joint2=...
    polycoef="0 MULTIPLIER 0 0 0"/>` in the MJCF.

    Why is this bad?
    A gripper whose second finger mimics the first falls open or jams: nothing drives the
    mimic joint.

    Example
    ```xml
    <robot name="gripper">
      <link name="palm"/><link name="left"/><link name="right"/>
      <joint name="left_joint" type="prismatic"><parent link="palm"/><child link="left"/>
        <axis xyz="1 0 0"/><limit lower="0" upper="0.04" effort="20" velocity="0.1"/></joint>
      <joint name="right_joint" type="prismatic"><parent link="palm"/><child link="right"/>
        <axis xyz="-1 0 0"/><limit lower="0" upper="0.04" effort="20" velocity="0.1"/>
        <mimic joint="left_joint"/></joint>
    </robot>
    ```

    Use instead (for MuJoCo: the URDF without `<mimic>`, and in the MJCF
    `<equality><joint joint1="right_joint" joint2="left_joint" polycoef="0 1 0 0 0"/></equality>`):
    ```xml
    <robot name="gripper">
      <link name="palm"/><link name="left"/><link name="right"/>
      <joint name="left_joint" type="prismatic"><parent link="palm"/><child link="left"/>
        <axis xyz="1 0 0"/><limit lower="0" upper="0.04" effort="20" velocity="0.1"/></joint>
      <joint name="right_joint" type="prismatic"><parent link="palm"/><child link="right"/>
        <axis xyz="-1 0 0"/><limit lower="0" upper="0.04" effort="20" velocity="0.1"/></joint>
    </robot>
    ```
    """
    names = {joint.name for joint in robot.joints}
    for joint in robot.joints:
        if joint.mimic is not None and joint.mimic.joint in names \
                and joint.mimic.joint != joint.name:
            yield Finding(f"joint '{joint.name}' mimics '{joint.mimic.joint}': MuJoCo's URDF "
                          "import drops <mimic>; add an <equality><joint> in the MJCF",
                          joint.mimic.where or joint.where, f"joint:{joint.name}")


#: Relative deviation of a prismatic axis' length from 1 that yourdfpy's motion shows.
_AXIS_TOLERANCE = 1e-6


@rule("C106", "yourdfpy-misreads", family=FAMILY, severity=Severity.WARNING, opt_in=True)
def yourdfpy_misreads(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds what yourdfpy (the Python URDF loader behind `robotdesc.to_yourdfpy`) refuses or
    reads differently from the URDF specification:

    - a `<capsule>` geometry: the load fails ("Unknown tag: capsule");
    - a planar or floating joint: its forward kinematics places the child at the joint's
      origin whatever the configuration;
    - a mimic joint whose leader is itself a mimic joint (or not a moving joint): the leader
      is taken as 0, so the chain does not move;
    - a prismatic joint whose axis is not of unit length: it moves by value x axis, not by
      value along the axis as URDF readers (urdfdom, Pinocchio) do.

    Off by default (a concern only for yourdfpy users): turn it on with `--select C106`.

    Why is this bad?
    Forward kinematics, scenes and collision checks computed with yourdfpy disagree with ROS,
    Gazebo and Pinocchio without any error, or the model does not load at all.

    Example
    ```xml
    <robot name="slider">
      <link name="base"/><link name="carriage"/>
      <joint name="slide" type="prismatic"><parent link="base"/><child link="carriage"/>
        <axis xyz="0 0 2"/><limit lower="0" upper="0.5" effort="10" velocity="0.1"/></joint>
    </robot>
    ```

    Use instead (a unit axis):
    ```xml
    <robot name="slider">
      <link name="base"/><link name="carriage"/>
      <joint name="slide" type="prismatic"><parent link="base"/><child link="carriage"/>
        <axis xyz="0 0 1"/><limit lower="0" upper="0.5" effort="10" velocity="0.1"/></joint>
    </robot>
    ```
    """
    for link in robot.links:
        for kind, number, shape in link.shapes():
            if isinstance(shape.geometry, Capsule):
                yield Finding(f"link '{link.name}' has a <capsule> {kind}: yourdfpy refuses "
                              "the whole model (\"Unknown tag: capsule\")",
                              shape.geometry.where or shape.where or link.where,
                              f"link:{link.name}/{kind}[{number}]")
    joints = {joint.name: joint for joint in robot.joints}
    for joint in robot.joints:
        if joint.type in ("planar", "floating"):
            yield Finding(f"{joint.type} joint '{joint.name}': yourdfpy's forward kinematics "
                          "keeps its child at the joint origin whatever the configuration",
                          joint.where, f"joint:{joint.name}")
        leader = joints.get(joint.mimic.joint) if joint.mimic is not None else None
        if joint.mimic is not None and leader is not None and leader is not joint and (
                leader.mimic is not None or leader.type not in tree.SCALAR_TYPES):
            why = "itself a mimic joint" if leader.mimic is not None else \
                f"a {leader.type} joint"
            yield Finding(f"joint '{joint.name}' mimics '{leader.name}', {why}: yourdfpy "
                          f"takes '{leader.name}' as 0, so '{joint.name}' does not follow it",
                          joint.mimic.where or joint.where, f"joint:{joint.name}")
        if joint.type == "prismatic" and joint.axis is not None:
            length = sum(c * c for c in joint.axis) ** 0.5
            if length > 0 and abs(length - 1.0) > _AXIS_TOLERANCE:
                yield Finding(f"prismatic joint '{joint.name}' has an axis of length "
                              f"{length:.6g}: yourdfpy moves it {length:.6g} times as far as "
                              "URDF readers do", joint.axis_where or joint.where,
                              f"joint:{joint.name}")
