"""A number that reached a macro body through a parameter names the call site that wrote it.

Issue 13, item 7: the finding points at the macro body's line, and the report adds "value
passed at file:line" (text), `passed_values` (JSON) and a related location (SARIF).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from lxml import etree

from robotdesc.expansion import ExpandOptions, expand_file
from robotdesc.source import PROVENANCE_ATTR, PassedValue, Span, decode_provenance, strip_provenance

ROBOT = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="shared_radius" value="0.1"/>
  <xacro:macro name="wheel" params="name mass radius:=0.05 *origin">
    <link name="${name}">
      <inertial>
        <xacro:insert_block name="origin"/>
        <mass value="${mass}"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
      </inertial>
      <collision><geometry><cylinder radius="${radius}" length="${shared_radius}"/></geometry></collision>
    </link>
  </xacro:macro>
  <xacro:macro name="side" params="prefix m">
    <xacro:wheel name="${prefix}_wheel" mass="${m * 1}">
      <origin xyz="0 0 ${m}"/>
    </xacro:wheel>
  </xacro:macro>
  <link name="base">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <xacro:wheel name="w1" mass="-2">
    <origin xyz="0 0 0"/>
  </xacro:wheel>
  <xacro:side prefix="left" m="-3"/>
  <joint name="j1" type="fixed"><parent link="base"/><child link="w1"/></joint>
  <joint name="j2" type="fixed"><parent link="base"/><child link="left_wheel"/></joint>
</robot>
"""


@pytest.fixture
def robot(tmp_path: Path) -> Path:
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(ROBOT)
    return path


def _where(robot: Path, xpath: str):
    expanded = expand_file(robot, options=ExpandOptions(use_cache=False))
    (element,) = etree.fromstring(expanded.xml).xpath(xpath)
    return decode_provenance(element.get(PROVENANCE_ATTR), expanded.files)


def test_a_value_passed_directly_names_its_call(robot: Path) -> None:
    where = _where(robot, "/robot/link[@name='w1']/inertial/mass")
    assert where.passed == (PassedValue("mass", "value", Span(str(robot), 22)),)


def test_through_nested_macros_the_outer_call_that_wrote_the_value(robot: Path) -> None:
    where = _where(robot, "/robot/link[@name='left_wheel']/inertial/mass")
    assert where.passed == (PassedValue("mass", "value", Span(str(robot), 25)),)
    assert where.macro_stack == (Span(str(robot), 15), Span(str(robot), 25))


def test_defaults_properties_and_blocks_are_not_passed_values(robot: Path) -> None:
    cylinder = _where(robot, "/robot/link[@name='w1']/collision/geometry/cylinder")
    assert cylinder.passed == ()  # radius is the macro's default; length a global property
    block = _where(robot, "/robot/link[@name='left_wheel']/inertial/origin")
    assert block.span == Span(str(robot), 16)  # written at the call, in the caller's scope
    assert block.passed == (PassedValue("origin", "xyz", Span(str(robot), 25)),)


def test_the_expanded_urdf_carries_no_trace(robot: Path) -> None:
    expanded = expand_file(robot, options=ExpandOptions(use_cache=False))
    assert PROVENANCE_ATTR.encode() not in strip_provenance(expanded.xml)


def _lint(robot: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "robotdesc", "lint", str(robot), *args],
                          check=False, capture_output=True, text=True, timeout=120,
                          env={"ROBOTDESC_CACHE_DIR": "off", "PATH": "/usr/bin:/bin"})


def test_text_report_says_where_the_value_was_passed(robot: Path) -> None:
    run = _lint(robot)
    assert run.returncode == 1, run.stderr
    assert f"= value passed at {robot}:22 (mass value)" in run.stdout
    assert f"= value passed at {robot}:25 (origin xyz, mass value)" in run.stdout


def test_json_and_sarif_carry_the_call_site(robot: Path) -> None:
    report = json.loads(_lint(robot, "--format", "json").stdout)
    by_element = {d["element"]: d for d in report["diagnostics"] if d["code"] == "I102"}
    assert by_element["link:w1/inertial"]["passed_values"] == [
        {"file": str(robot), "line": 22, "values": ["mass value"]}]
    sarif = json.loads(_lint(robot, "--format", "sarif").stdout)
    results = [r for r in sarif["runs"][0]["results"] if r["ruleId"] == "I102"]
    texts = [loc["message"]["text"] for r in results for loc in r["relatedLocations"]]
    assert "value passed at this call (mass value)" in texts
    lines = {loc["physicalLocation"]["region"]["startLine"]
             for r in results for loc in r["relatedLocations"]}
    assert {22, 25} <= lines
