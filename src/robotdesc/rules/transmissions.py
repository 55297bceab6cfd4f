"""Transmission rules (T): ros_control `<transmission>` blocks must be loadable."""

from __future__ import annotations

from collections.abc import Iterator

from robotdesc.diagnostics import Finding, Severity
from robotdesc.model.elements import Robot, Transmission
from robotdesc.rules.registry import RuleContext, rule

FAMILY = "transmissions"

#: Types loaded by ros_control's transmission parser. Older types (PR2's mechanism model:
#: `SimpleTransmission`, `WristTransmission`, `pr2_mechanism_model/...`) have their own
#: elements and no hardware interfaces, so only the joint names are checked for them.
_ROS_CONTROL_PREFIX = "transmission_interface/"


def _is_ros_control(transmission: Transmission) -> bool:
    return transmission.type.startswith(_ROS_CONTROL_PREFIX)


def _element(transmission: Transmission) -> str:
    return f"transmission:{transmission.name}"


@rule("T101", "transmission-joint-missing", family=FAMILY, severity=Severity.ERROR)
def transmission_joint_missing(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a transmission whose `<joint name=...>` names no joint of the robot, or a
    ros_control transmission (type `transmission_interface/...`) without any `<joint>`.

    Why is this bad?
    ros_control (and gazebo_ros_control) fail to load the transmission, so the joint it
    was meant for gets no controller interface. Usually a joint renamed without its
    transmission.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
      <transmission name="shoulder_trans">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="shoulder_joint">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="shoulder_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
      </transmission>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
      <transmission name="shoulder_trans">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="shoulder">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="shoulder_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
      </transmission>
    </robot>
    ```
    """
    joints = {joint.name for joint in robot.joints}
    for transmission in robot.transmissions:
        if not transmission.joints and _is_ros_control(transmission):
            yield Finding(f"transmission '{transmission.name}' names no joint",
                          transmission.where, _element(transmission))
        for joint in transmission.joints:
            if joint.name not in joints:
                yield Finding(f"transmission '{transmission.name}' names joint "
                              f"'{joint.name}', which is not defined",
                              joint.where or transmission.where, _element(transmission))


@rule("T102", "transmission-without-actuator", family=FAMILY, severity=Severity.ERROR)
def transmission_without_actuator(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a ros_control transmission (type `transmission_interface/...`) without an
    `<actuator>`.

    Why is this bad?
    ros_control's transmission parser requires at least one actuator and skips the
    transmission without it, so the joint is left without a controller interface.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
      <transmission name="shoulder_trans">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="shoulder">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
      </transmission>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
      <transmission name="shoulder_trans">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="shoulder">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="shoulder_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
      </transmission>
    </robot>
    ```
    """
    for transmission in robot.transmissions:
        if _is_ros_control(transmission) and not transmission.actuators:
            yield Finding(f"transmission '{transmission.name}' has no <actuator>",
                          transmission.where, _element(transmission))


@rule("T103", "transmission-without-hardware-interface", family=FAMILY,
      severity=Severity.ERROR)
def transmission_without_hardware_interface(robot: Robot, ctx: RuleContext
                                            ) -> Iterator[Finding]:
    """Finds a transmission joint that declares no `<hardwareInterface>` (neither on the
    joint nor on an actuator of the transmission).

    Only ros_control transmissions (type `transmission_interface/...`) are checked;
    PR2-era types have no hardware interfaces.

    Why is this bad?
    gazebo_ros_control and ros_control's resource managers need to know whether the joint
    takes position, velocity or effort commands; without an interface the transmission is
    skipped and the joint cannot be controlled.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
      <transmission name="shoulder_trans">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="shoulder"/>
        <actuator name="shoulder_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
      </transmission>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
      <transmission name="shoulder_trans">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="shoulder">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="shoulder_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
      </transmission>
    </robot>
    ```
    """
    for transmission in robot.transmissions:
        if not _is_ros_control(transmission):
            continue
        on_actuators = any(a.hardware_interfaces for a in transmission.actuators)
        for joint in transmission.joints:
            if not any(joint.hardware_interfaces) and not on_actuators:
                yield Finding(f"transmission '{transmission.name}' joint '{joint.name}' "
                              "declares no <hardwareInterface>",
                              joint.where or transmission.where, _element(transmission))
