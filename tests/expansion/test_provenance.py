"""Every expanded element knows its xacro file:line and its macro call chain."""

from __future__ import annotations

from pathlib import Path

import pytest
from lxml import etree

from robotdesc.expansion import ExpandOptions, expand_file
from robotdesc.source import PROVENANCE_ATTR, Span, decode_provenance

WS = Path(__file__).parent / "fixtures" / "ws" / "src"
ROBOT = WS / "robot_pkg" / "urdf" / "robot.urdf.xacro"
ARM = WS / "arm_pkg" / "urdf" / "arm.xacro"
PARTS = WS / "robot_pkg" / "urdf" / "parts.xacro"


@pytest.fixture(scope="module")
def expanded():
    return expand_file(ROBOT, options=ExpandOptions(use_cache=False))


def _provenance(expanded, xpath):
    root = etree.fromstring(expanded.xml)
    (element,) = root.xpath(xpath)
    return decode_provenance(element.get(PROVENANCE_ATTR), expanded.files)


def test_top_level_element_points_at_its_line(expanded):
    where = _provenance(expanded, "/robot/link[@name='base_link']")
    assert where.span == Span(str(ROBOT), 6)
    assert where.macro_stack == ()


def test_macro_body_element_carries_each_call_site(expanded):
    upper = _provenance(expanded, "/robot/link[@name='upper']")
    lower = _provenance(expanded, "/robot/link[@name='lower']")
    assert upper.span == lower.span == Span(str(ARM), 4)
    assert upper.macro_stack == (Span(str(ROBOT), 7),)
    assert lower.macro_stack == (Span(str(ROBOT), 8),)


def test_nested_macro_chain_is_innermost_first(expanded):
    limit = _provenance(expanded, "/robot/joint[@name='tool_joint']/limit")
    assert limit.span == Span(str(ARM), 15)
    assert limit.macro_stack == (Span(str(PARTS), 4), Span(str(ROBOT), 9))


def test_packages_resolved_with_their_source(expanded):
    sources = {p.name: p.source for p in expanded.packages}
    assert sources == {"arm_pkg": "workspace", "robot_pkg": "enclosing"}
    assert str(ARM) in expanded.files_read and str(PARTS) in expanded.files_read


def test_arguments_reach_the_document():
    expanded = expand_file(ROBOT, {"length": "0.7"}, options=ExpandOptions(use_cache=False))
    origins = etree.fromstring(expanded.xml).xpath("/robot/joint[@name='upper_joint']/origin/@xyz")
    assert origins == ["0 0 0.7"]


def test_optenv_sees_only_allowlisted_variables(monkeypatch):
    monkeypatch.setenv("ROBOTDESC_TEST_SUFFIX", "secret")
    safe = expand_file(ROBOT, options=ExpandOptions(use_cache=False))
    allowed = expand_file(ROBOT, options=ExpandOptions(use_cache=False,
                                                       env_allowlist=("ROBOTDESC_TEST_SUFFIX",)))
    assert etree.fromstring(safe.xml).xpath("/robot/link[last()]/@name") == ["plain_marker"]
    assert etree.fromstring(allowed.xml).xpath("/robot/link[last()]/@name") == ["secret_marker"]


def test_recursion_depth_is_recorded(tmp_path):
    source = tmp_path / "chain.urdf.xacro"
    source.write_text(
        '<robot name="c" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="base"/>\n'
        '  <xacro:macro name="chain" params="i">\n'
        '    <link name="c${i}"/>\n'
        '    <xacro:if value="${i > 0}"><xacro:chain i="${i-1}"/></xacro:if>\n'
        '  </xacro:macro>\n'
        '  <xacro:chain i="9"/>\n'
        '</robot>\n')
    (record,) = expand_file(source, options=ExpandOptions(use_cache=False)).macro_recursion
    assert (record.macro, record.depth) == ("chain", 10)
    assert record.defined_at == Span(str(source), 3)
    assert record.called_at == Span(str(source), 7)


def test_find_in_an_expression_resolves_the_package(tmp_path):
    import shutil

    workspace = shutil.copytree(WS.parent, tmp_path / "ws") / "src"
    robot = workspace / "robot_pkg" / "urdf" / "find_expr.urdf.xacro"
    robot.write_text(
        '<robot name="f" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="${find(\'arm_pkg\') + \'/urdf/arm.xacro\'}"/>\n'
        '  <link name="base"/>\n'
        '  <xacro:arm_segment name="upper" parent="base" length="0.2"/>\n'
        '</robot>\n')
    expanded = expand_file(robot, options=ExpandOptions(use_cache=False))
    assert b'name="upper"' in expanded.xml
    assert str(workspace / "arm_pkg" / "urdf" / "arm.xacro") in expanded.files_read


def test_a_provenance_attribute_written_in_the_file_is_replaced(tmp_path):
    robot = tmp_path / "robot.urdf.xacro"
    robot.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                     f'  <link name="a" {PROVENANCE_ATTR}="9:99" type="x"/>\n</robot>\n')
    expanded = expand_file(robot, options=ExpandOptions(use_cache=False))
    (link,) = etree.fromstring(expanded.xml).xpath("/robot/link")
    assert sorted(link.attrib) == sorted(["name", PROVENANCE_ATTR, "type"])
    assert decode_provenance(link.get(PROVENANCE_ATTR), expanded.files).span == Span(str(robot), 2)
