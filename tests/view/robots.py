"""A small description package for the view and report tests: primitives, an STL mesh used
twice, a mimic joint, inertials (one of them implausible, so that lint finds something)."""

from __future__ import annotations

from pathlib import Path

from mesh.builders import box_triangles, write_binary_stl

URDF = """<?xml version="1.0"?>
<robot name="demo">
  <material name="blue"><color rgba="0.1 0.2 0.9 1"/></material>
  <link name="base">
    <inertial><mass value="2"/>
      <inertia ixx="0.00833" ixy="0" ixz="0" iyy="0.02833" iyz="0" izz="0.03333"/></inertial>
    <visual><geometry><box size="0.4 0.2 0.1"/></geometry><material name="blue"/></visual>
    <collision><geometry><box size="0.4 0.2 0.1"/></geometry></collision>
  </link>
  <link name="arm">
    <inertial><origin xyz="0 0 0.1"/><mass value="1"/>
      <inertia ixx="0.0035" ixy="0" ixz="0" iyy="0.0035" iyz="0" izz="0.0005"/></inertial>
    <visual><origin xyz="0 0 0.1"/>
      <geometry><mesh filename="package://demo/meshes/block.stl" scale="0.05 0.05 0.2"/></geometry>
    </visual>
    <collision><origin xyz="0 0 0.1"/>
      <geometry><cylinder radius="0.03" length="0.2"/></geometry></collision>
  </link>
  <link name="finger_left">
    <inertial><mass value="0.1"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="0.5"/></inertial>
    <visual><geometry><mesh filename="package://demo/meshes/block.stl" scale="0.01 0.01 0.05"/>
      </geometry></visual>
  </link>
  <link name="finger_right">
    <inertial><mass value="0.1"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <visual><geometry><mesh filename="package://demo/meshes/block.stl" scale="0.01 0.01 0.05"/>
      </geometry></visual>
    <collision><geometry><mesh filename="package://demo/meshes/missing.stl"/></geometry>
    </collision>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.05"/><axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>
  </joint>
  <joint name="grip" type="prismatic">
    <parent link="arm"/><child link="finger_left"/>
    <origin xyz="0 0.02 0.2"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="0.04" effort="5" velocity="0.1"/>
  </joint>
  <joint name="grip_mirror" type="prismatic">
    <parent link="arm"/><child link="finger_right"/>
    <origin xyz="0 -0.02 0.2"/><axis xyz="0 1 0"/>
    <limit lower="-0.04" upper="0" effort="5" velocity="0.1"/>
    <mimic joint="grip" multiplier="-1" offset="0"/>
  </joint>
</robot>
"""

PACKAGE_XML = """<?xml version="1.0"?>
<package format="3"><name>demo</name><version>0.0.1</version>
<description>test</description><maintainer email="a@b.c">t</maintainer>
<license>MIT</license></package>
"""


def write_demo_package(root: Path) -> Path:
    """Write the `demo` package under `root`; returns the URDF's path."""
    package = root / "demo"
    (package / "meshes").mkdir(parents=True)
    (package / "urdf").mkdir()
    (package / "package.xml").write_text(PACKAGE_XML)
    write_binary_stl(package / "meshes" / "block.stl", box_triangles((1.0, 1.0, 1.0)))
    urdf = package / "urdf" / "demo.urdf"
    urdf.write_text(URDF)
    return urdf
