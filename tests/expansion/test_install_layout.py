"""`$(find pkg)/x` where x exists only in the package's installed layout (issue 13: real
packages such as ros2_control_demos install `description/ros2_control` as `ros2_control`)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from robotdesc.expansion import ExpandOptions, expand_file
from robotdesc.expansion.install_layout import (
    InstallRule,
    parse_install_rules,
    source_of_installed,
)

CMAKE = """
cmake_minimum_required(VERSION 3.16)
project(demo_example_1)
install(
  DIRECTORY description/launch description/ros2_control description/urdf
  DESTINATION share/${PROJECT_NAME}
)
install(DIRECTORY hardware/include/ DESTINATION include/demo_example_1)
install(DIRECTORY config/ DESTINATION share/${PROJECT_NAME}/params)  # contents only
install(FILES extra/robot.srdf DESTINATION share/demo_example_1/srdf)
install(DIRECTORY ../escape DESTINATION share/${PROJECT_NAME})
install(DIRECTORY other DESTINATION share/another_package)
# install(DIRECTORY commented DESTINATION share/${PROJECT_NAME})
"""


def test_rules_read_from_cmake() -> None:
    rules = parse_install_rules(CMAKE, "demo_example_1")
    assert rules == (
        InstallRule("launch", "description/launch", True),
        InstallRule("ros2_control", "description/ros2_control", True),
        InstallRule("urdf", "description/urdf", True),
        InstallRule("params", "config", True),
        InstallRule("srdf/robot.srdf", "extra/robot.srdf", False),
    )


def test_catkin_and_ament_auto_forms() -> None:
    catkin = "install(DIRECTORY meshes urdf DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})"
    assert [r.installed for r in parse_install_rules(catkin, "p")] == ["meshes", "urdf"]
    auto = "ament_auto_package(INSTALL_TO_SHARE gazebo description/urdf)"
    assert parse_install_rules(auto, "p") == (InstallRule("gazebo", "gazebo", True),
                                             InstallRule("urdf", "description/urdf", True))


def _package(root: Path) -> Path:
    package = root / "demo_example_1"
    (package / "description" / "ros2_control").mkdir(parents=True)
    (package / "description" / "urdf").mkdir(parents=True)
    (package / "CMakeLists.txt").write_text(CMAKE)
    (package / "package.xml").write_text(
        "<package format='3'><name>demo_example_1</name></package>")
    (package / "description" / "ros2_control" / "demo.ros2_control.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:macro name="demo_control"><ros2_control name="demo" type="system"/>'
        "</xacro:macro>\n</robot>\n")
    top = package / "description" / "urdf" / "demo.urdf.xacro"
    top.write_text(
        '<robot name="demo" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="$(find demo_example_1)/ros2_control/'
        'demo.ros2_control.xacro"/>\n'
        '  <link name="base"/>\n  <xacro:demo_control/>\n</robot>\n')
    return top


def test_source_of_installed(tmp_path: Path) -> None:
    top = _package(tmp_path)
    package = str(tmp_path / "demo_example_1")
    found = source_of_installed(package, "demo_example_1", "ros2_control/demo.ros2_control.xacro")
    assert found == str(top.parent.parent / "ros2_control" / "demo.ros2_control.xacro")
    assert source_of_installed(package, "demo_example_1", "ros2_control/missing.xacro") is None


def test_include_of_an_installed_path_expands_in_the_sandbox(tmp_path: Path) -> None:
    top = _package(tmp_path)
    expanded = expand_file(top, options=ExpandOptions(use_cache=False))
    assert b'name="demo" type="system"' in expanded.xml
    assert str(top.parent.parent / "ros2_control" / "demo.ros2_control.xacro") in expanded.files


def test_cli_expands_it(tmp_path: Path) -> None:
    top = _package(tmp_path)
    run = subprocess.run([sys.executable, "-m", "robotdesc", "expand", str(top)], check=False,
                         capture_output=True, text=True, timeout=120,
                         env={"ROBOTDESC_CACHE_DIR": "off", "PATH": "/usr/bin:/bin"})
    assert run.returncode == 0, run.stderr
    assert "<ros2_control" in run.stdout
