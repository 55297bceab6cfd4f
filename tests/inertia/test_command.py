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
