"""Helpers shared by tests (importable as `support`: pyproject puts tests/ on sys.path)."""

from __future__ import annotations

import sysconfig
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def example_robot_data_dir() -> Path | None:
    """The robots/ folder of the installed example-robot-data, if present."""
    root = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix/share/example-robot-data/robots"
    return root if root.is_dir() else None


def example_robot_urdfs() -> list[Path]:
    """Every URDF shipped by example-robot-data (empty when it is not installed)."""
    root = example_robot_data_dir()
    return sorted(root.rglob("*.urdf")) if root else []


#: A xacro robot whose included macro (`part.xacro`) has a joint limit to fill in: with
#: `LOWER`/`UPPER` replaced by `limit_robot_files` it is reversed (J103) or not; for the
#: cache tests (whole results, replays).
LIMIT_ROBOT_TOP = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="part.xacro"/>
  <link name="base">
    <inertial><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <xacro:arm parent="base"/>
</robot>
"""
LIMIT_ROBOT_PART = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm" params="parent">
    <link name="arm">
      <inertial><mass value="1"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    </link>
    <joint name="shoulder" type="revolute">
      <parent link="${parent}"/><child link="arm"/><axis xyz="0 0 1"/>
      <limit lower="LOWER" upper="UPPER" effort="10" velocity="1"/>
    </joint>
  </xacro:macro>
</robot>
"""


def write_limit_robot(folder: Path, lower: str = "1") -> Path:
    """The robot above in `folder` (made if needed), its limit reversed (J103) unless
    `lower` is "-1"; returns the top file."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "part.xacro").write_text(LIMIT_ROBOT_PART.replace("LOWER", lower).replace(
        "UPPER", "1" if lower == "-1" else "-1"))
    top = folder / "robot.urdf.xacro"
    top.write_text(LIMIT_ROBOT_TOP)
    return top
