"""`robotdesc inertia`: table, JSON, --suggest and --write on a small package."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from mesh.builders import box_triangles, write_binary_stl

from robotdesc.cli import main

URDF = """<?xml version="1.0"?>
<robot name="r">
  <link name="base"/>
  <link name="arm">
    <inertial>
      <mass value="1"/>
      <inertia ixx="16666700" ixy="0" ixz="0" iyy="14166700" iyz="0" izz="4166670"/>
    </inertial>
    <collision><geometry><mesh filename="package://pkg/meshes/box.stl"/></geometry></collision>
  </link>
  <joint name="j" type="continuous"><parent link="base"/><child link="arm"/></joint>
</robot>
"""


@pytest.fixture
def robot_file(tmp_path: Path) -> Path:
    package = tmp_path / "pkg"
    (package / "meshes").mkdir(parents=True)
    (package / "package.xml").write_text("<package format='3'><name>pkg</name></package>")
    write_binary_stl(package / "meshes" / "box.stl", box_triangles((0.1, 0.2, 0.4)))
    path = package / "robot.urdf"
    path.write_text(URDF)
    return path


def test_table_names_the_source_and_the_error(robot_file: Path, capsys) -> None:
    assert main(["inertia", str(robot_file)]) == 0
    out = capsys.readouterr().out
    assert out.startswith("LINK") and "collision" in out and "g*mm^2" in out


def test_json(robot_file: Path, capsys) -> None:
    assert main(["inertia", str(robot_file), "--format", "json"]) == 0
    [row] = json.loads(capsys.readouterr().out)["links"]
    assert row["link"] == "arm" and row["volume"] == pytest.approx(0.008)
    assert row["derived_moments"] == pytest.approx([0.0041667, 0.0141667, 0.0166667], rel=1e-4)


def test_suggest_and_write(robot_file: Path, tmp_path: Path, capsys) -> None:
    assert main(["inertia", str(robot_file), "--suggest"]) == 0
    out = capsys.readouterr().out
    assert f"replaces the <inertial> at {robot_file}:5" in out and 'ixx="0.0166667"' in out
    patch = tmp_path / "fix.patch"
    assert main(["inertia", str(robot_file), "--write", str(patch)]) == 0
    assert '+      <inertia ixx="0.0166667"' in patch.read_text()
    assert robot_file.read_text() == URDF


STUB = """<?xml version="1.0"?>
<robot name="hip">
  <link name="base"/>
  <link name="hip_yaw_link">
    <inertial><origin xyz="-0.06 0 0.008"/><mass value="2.965"/>
      <inertia ixx="0.0036" ixy="0" ixz="0" iyy="0.0050" iyz="0" izz="0.0058"/></inertial>
    <visual><origin xyz="-0.06 0 0"/><geometry><box size="0.16 0.08 0.08"/></geometry></visual>
    <collision><origin xyz="0.02 0 0" rpy="0 1.5707963 0"/>
      <geometry><cylinder radius="0.01" length="0.02"/></geometry></collision>
  </link>
  <joint name="hip_yaw" type="revolute"><parent link="base"/><child link="hip_yaw_link"/>
    <axis xyz="0 0 1"/><limit lower="-0.4" upper="0.4" effort="200" velocity="23"/></joint>
</robot>
"""


def test_no_suggestion_from_a_stand_in_denser_than_any_material(tmp_path: Path, capsys) -> None:
    """A 2 cm collision stub under a 3 kg hip would hold it at 4.7e5 kg/m^3: the stub is not
    the body, and a tensor from it would be 25x too small (held-out)."""
    path = tmp_path / "hip.urdf"
    path.write_text(STUB)
    assert main(["inertia", str(path), "--suggest"]) == 0
    captured = capsys.readouterr()
    assert "<inertia" not in captured.out
    assert "denser than any material" in captured.err and "--source visual" in captured.err


ROOT = """<?xml version="1.0"?>
<robot name="mobile">
  <link name="base_footprint"><visual><geometry><box size="0.001 0.001 0.001"/></geometry></visual></link>
  <link name="base_link">
    <inertial><origin xyz="0 0 0.1"/><mass value="20"/>
      <inertia ixx="0.25" ixy="0" ixz="0" iyy="0.25" iyz="0" izz="0.33"/></inertial>
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.4 0.4 0.2"/></geometry></collision>
  </link>
  <joint name="footprint_joint" type="fixed"><parent link="base_footprint"/><child link="base_link"/></joint>
  <link name="camera"><visual><geometry><box size="0.02 0.08 0.02"/></geometry></visual></link>
  <joint name="camera_joint" type="fixed"><parent link="base_link"/><child link="camera"/></joint>
  <link name="wheel"><collision><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision></link>
  <joint name="wheel_joint" type="continuous"><parent link="base_link"/><child link="wheel"/></joint>
</robot>
"""


def test_a_massless_root_and_frames_are_left_massless(tmp_path: Path, capsys) -> None:
    """go1's `base` and PR2's `base_footprint` were offered a 1e-6 kg inertial; the docs say
    a massless root is the fix. A moving link without one still gets its block."""
    path = tmp_path / "mobile.urdf"
    path.write_text(ROOT)
    assert main(["inertia", str(path), "--suggest"]) == 0
    out = capsys.readouterr().out
    assert "link 'wheel'" in out
    assert "base_footprint" not in out and "link 'camera'" not in out
