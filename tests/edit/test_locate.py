"""Where a fix's edit goes, one test per kind, through `robotdesc lint --fix` as a user runs
it: the literal in a macro body, the argument at the call site, the value of the one
`xacro:property` that carries it, and refused (display-only, naming the package-relative
FILE:LINE) on an expression."""

from __future__ import annotations

import pytest
from linting.test_fix import make_package

from robotdesc.cli import main
from robotdesc.edit.fix import Applicability
from robotdesc.linting.driver import lint_file
from robotdesc.linting.fix import plan_fixes

HEAD = '<?xml version="1.0"?>\n<robot name="p" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'


def _joint(name: str, axis: str, child: str) -> str:
    return (f'  <link name="{child}"/>\n  <joint name="{name}" type="continuous">'
            f'<parent link="base"/><child link="{child}"/><axis xyz="{axis}"/></joint>\n')


@pytest.fixture(autouse=True)
def _own_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", str(tmp_path / "cache"))


def test_macro_body_literal(tmp_path):
    robot = (HEAD + '  <link name="base"/>\n  <xacro:macro name="w" params="n">\n'
             + _joint("j${n}", "0 2 0", "c${n}") + '  </xacro:macro>\n'
             '  <xacro:w n="1"/>\n  <xacro:w n="2"/>\n</robot>\n')
    path = make_package(tmp_path, robot)
    main(["lint", str(path), "--fix", "--select", "J107"])
    assert path.read_text() == robot.replace('xyz="0 2 0"', 'xyz="0 1 0"')


def test_call_site_argument(tmp_path):
    robot = (HEAD + '  <link name="base"/>\n  <xacro:macro name="w" params="n axis">\n'
             + _joint("j${n}", "${axis}", "c${n}") + '  </xacro:macro>\n'
             '  <xacro:w n="1" axis="0 0 5"/>\n  <xacro:w n="2" axis="0 0 1"/>\n</robot>\n')
    path = make_package(tmp_path, robot)
    main(["lint", str(path), "--fix", "--select", "J107"])
    assert path.read_text() == robot.replace('axis="0 0 5"', 'axis="0 0 1"')


PROPERTY = (HEAD + '  <xacro:property name="pitch_axis" value="0 3 0"/>\n'
            '  <link name="base"/>\n' + _joint("a", "${pitch_axis}", "ca")
            + _joint("b", "${pitch_axis}", "cb") + '</robot>\n')


def test_property_value_is_edited_when_every_use_wants_the_change(tmp_path, capsys):
    path = make_package(tmp_path, PROPERTY)
    main(["lint", str(path), "--fix", "--select", "J107"])
    assert path.read_text() == PROPERTY.replace('value="0 3 0"', 'value="0 1 0"')
    assert "fixed 1 finding(s) in 1 file(s)" in capsys.readouterr().err  # one edit (issue 34)


def test_property_used_elsewhere_is_refused_naming_its_line(tmp_path, capsys):
    robot = PROPERTY.replace('</robot>', '  <link name="v"><visual><origin xyz="${pitch_axis}"/>'
                             '<geometry><box size="1 1 1"/></geometry></visual></link>\n</robot>')
    path = make_package(tmp_path, robot)
    main(["lint", str(path), "--fix", "--select", "J107"])
    err = capsys.readouterr().err
    assert path.read_text() == robot
    assert "J107 fix not applicable: the value at urdf/robot.urdf.xacro:3 is used in 3 places" in err


def test_property_with_an_expression_is_refused_at_the_property(tmp_path, capsys):
    robot = PROPERTY.replace('value="0 3 0"', 'value="0 ${2 + 1} 0"')
    path = make_package(tmp_path, robot)
    main(["lint", str(path), "--fix", "--select", "J107"])
    err = capsys.readouterr().err
    assert path.read_text() == robot
    assert ("fix not applicable: computed at urdf/robot.urdf.xacro:3: the property "
            "'pitch_axis' has no literal value") in err


def test_expression_is_refused_display_only_with_the_relative_line(tmp_path):
    robot = (HEAD + '  <link name="base"/>\n' + _joint("a", "0 ${1 + 1} 0", "ca") + '</robot>\n')
    path = make_package(tmp_path, robot)
    [outcome] = plan_fixes([lint_file(str(path), select=["J107"])]).outcomes
    assert outcome.fix.applicability is Applicability.DISPLAY_ONLY and not outcome.fix.edits
    assert outcome.reason == "computed at urdf/robot.urdf.xacro:5: the expression '0 ${1 + 1} 0'"


def test_property_passed_as_an_argument_is_edited_at_the_property(tmp_path):
    robot = (HEAD + '  <xacro:property name="up" value="0 0 4"/>\n  <link name="base"/>\n'
             '  <xacro:macro name="w" params="n axis">\n' + _joint("j${n}", "${axis}", "c${n}")
             + '  </xacro:macro>\n  <xacro:w n="1" axis="${up}"/>\n</robot>\n')
    path = make_package(tmp_path, robot)
    main(["lint", str(path), "--fix", "--select", "J107"])
    assert path.read_text() == robot.replace('value="0 0 4"', 'value="0 0 1"')
