"""Robots built in the tests: a small four-wheel skid-steer rover and a torus over a pole."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

WHEEL_RADIUS, TRACK, WHEELBASE = 0.06, 0.36, 0.2


def rover_urdf(directory: Path, with_config: bool = True) -> Path:
    """A 10 kg four-wheel rover (0.06 m wheels, 0.36 m apart) in a ROS-like package
    `rover_description`, its diff_drive_controller configured in a sibling `rover_control`."""
    package = directory / "rover_description"
    (package / "urdf").mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>rover_description</name></package>")
    wheels = []
    for side, y in (("left", TRACK / 2), ("right", -TRACK / 2)):
        for end, x in (("front", WHEELBASE / 2), ("rear", -WHEELBASE / 2)):
            name = f"{side}_{end}_wheel"
            wheels.append(f"""
  <link name="{name}_link">
    <inertial><mass value="0.5"/>
      <inertia ixx="0.0005" ixy="0" ixz="0" iyy="0.0009" iyz="0" izz="0.0005"/></inertial>
    <collision><origin xyz="0 0 0" rpy="{math.pi / 2} 0 0"/>
      <geometry><cylinder radius="{WHEEL_RADIUS}" length="0.04"/></geometry></collision>
  </link>
  <joint name="{name}" type="continuous">
    <parent link="base_link"/><child link="{name}_link"/>
    <origin xyz="{x} {y} 0" rpy="0 0 0"/><axis xyz="0 1 0"/>
    <limit effort="20" velocity="50"/><dynamics damping="0.01" friction="0"/>
  </joint>""")
    path = package / "urdf" / "rover.urdf"
    path.write_text(f"""<?xml version="1.0"?>
<robot name="rover">
  <link name="base_link">
    <inertial><mass value="8"/>
      <inertia ixx="0.07" ixy="0" ixz="0" iyy="0.12" iyz="0" izz="0.17"/></inertial>
    <collision><origin xyz="0 0 0.04"/><geometry><box size="0.4 0.26 0.08"/></geometry></collision>
  </link>{''.join(wheels)}
</robot>
""")
    if with_config:
        config = directory / "rover_control" / "config"
        config.mkdir(parents=True)
        (config / "rover_controllers.yaml").write_text(f"""controller_manager:
  ros__parameters:
    diff_drive: {{type: diff_drive_controller/DiffDriveController}}
diff_drive:
  ros__parameters:
    left_wheel_names: [left_front_wheel, left_rear_wheel]
    right_wheel_names: [right_front_wheel, right_rear_wheel]
    wheel_separation: {TRACK}
    wheel_radius: {WHEEL_RADIUS}
""")
    return path


def torus_triangles(major: float, minor: float, rings: int = 32,
                    sides: int = 12) -> np.ndarray:
    """(n, 3, 3) triangles of a torus about z, wound outward (m)."""
    u = np.linspace(0, 2 * np.pi, rings, endpoint=False)
    v = np.linspace(0, 2 * np.pi, sides, endpoint=False)
    uu, vv = np.meshgrid(u, v, indexing="ij")
    points = np.stack([(major + minor * np.cos(vv)) * np.cos(uu),
                       (major + minor * np.cos(vv)) * np.sin(uu), minor * np.sin(vv)], axis=-1)
    triangles = []
    for i in range(rings):
        for j in range(sides):
            a, b = points[i, j], points[(i + 1) % rings, j]
            c, d = points[(i + 1) % rings, (j + 1) % sides], points[i, (j + 1) % sides]
            triangles += [(a, b, c), (a, c, d)]
    return np.asarray(triangles)


def torus_over_pole_urdf(directory: Path, major: float = 0.1, minor: float = 0.02,
                         pole_radius: float = 0.01, pole_height: float = 0.3,
                         start: float = 0.45) -> Path:
    """A fixed thin pole and a free torus (mass 1 kg) whose hole is centred above it."""
    from robotdesc.sim.dart_urdf import write_stl

    write_stl(str(directory / "torus.stl"), torus_triangles(major, minor))
    ixx, izz = major ** 2 / 2 + 5 * minor ** 2 / 8, major ** 2 + 3 * minor ** 2 / 4
    path = directory / "torus_pole.urdf"
    path.write_text(f"""<?xml version="1.0"?>
<robot name="torus_pole">
  <link name="world"/>
  <link name="pole">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><origin xyz="0 0 {pole_height / 2}"/>
      <geometry><cylinder radius="{pole_radius}" length="{pole_height}"/></geometry></collision>
  </link>
  <joint name="pole_fixed" type="fixed"><parent link="world"/><child link="pole"/></joint>
  <link name="torus">
    <inertial><mass value="1"/>
      <inertia ixx="{ixx}" ixy="0" ixz="0" iyy="{ixx}" iyz="0" izz="{izz}"/></inertial>
    <collision><geometry><mesh filename="torus.stl"/></geometry></collision>
  </link>
  <joint name="torus_free" type="floating"><parent link="world"/><child link="torus"/>
    <origin xyz="0 0 {start}"/></joint>
</robot>
""")
    return path
