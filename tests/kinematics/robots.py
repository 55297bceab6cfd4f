"""Small robots written inline for the kinematics and srdf tests."""

from __future__ import annotations

from robotdesc.model.elements import Robot
from robotdesc.model.parse import parse_urdf

INERTIA = '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>'


def robot(text: str, path: str = "robot.urdf") -> Robot:
    return parse_urdf(text.encode(), path)


#: base (box) - shoulder (continuous) - upper (box) - elbow (revolute) - fore (box),
#: plus a geometry-less wrist link and a hand box beyond it; fore overlaps base at zero.
ARM = f"""<robot name="arm">
  <link name="base"><inertial><mass value="5"/>{INERTIA}</inertial>
    <collision><geometry><box size="0.4 0.4 0.4"/></geometry></collision></link>
  <link name="upper"><inertial><origin xyz="0 0 0.1"/><mass value="2"/>{INERTIA}</inertial>
    <collision><geometry><box size="0.1 0.1 0.3"/></geometry></collision></link>
  <link name="fore"><inertial><mass value="1"/>{INERTIA}</inertial>
    <collision><origin xyz="0 0 -0.45"/><geometry><box size="0.1 0.1 0.3"/></geometry></collision></link>
  <link name="wrist"/>
  <link name="hand"><inertial><mass value="0.5"/>{INERTIA}</inertial>
    <collision><geometry><sphere radius="0.05"/></geometry></collision></link>
  <joint name="shoulder" type="continuous"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 1 0"/>
    <limit lower="-0.5" upper="0.5" effort="10" velocity="1"/></joint>
  <joint name="wrist_joint" type="fixed"><parent link="fore"/><child link="wrist"/>
    <origin xyz="0 0 0.2"/></joint>
  <joint name="hand_joint" type="prismatic"><parent link="wrist"/><child link="hand"/>
    <axis xyz="0 0 1"/><limit lower="0.1" upper="0.2" effort="10" velocity="1"/></joint>
  <joint name="hand_twin" type="prismatic"><parent link="base"/><child link="twin"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/>
    <mimic joint="hand_joint" multiplier="2" offset="0.1"/></joint>
  <link name="twin"/>
</robot>"""
