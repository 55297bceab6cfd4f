"""A save that changes only literal values is linted on the previous expansion edited in
place (no xacro run), with the findings a full expansion gives; anything else expands again."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from robotdesc.expansion import expand_file
from robotdesc.linting import driver
from robotdesc.server.edits import ValueChange, literal_changes, patch_document
from robotdesc.server.session import Session

TOP = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="part.xacro"/>
  <link name="base">
    <inertial><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <xacro:arm parent="base" side="left"/>
  <xacro:arm parent="base" side="right"/>
</robot>
"""
PART = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="reach" value="1"/>
  <xacro:macro name="arm" params="parent side">
    <link name="${side}_arm">
      <inertial><mass value="1"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    </link>
    <joint name="${side}_shoulder" type="revolute">
      <parent link="${parent}"/><child link="${side}_arm"/>
      <axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" effort="10" velocity="1"/>
    </joint>
  </xacro:macro>
</robot>
"""


def test_literal_changes_are_found_and_anything_else_refused() -> None:
    before = PART.encode()
    swapped = before.replace(b'lower="-1" upper="1"', b'lower="1" upper="-1"')
    assert literal_changes(before, swapped) == (ValueChange(12, "lower", "-1", "1"),
                                                ValueChange(12, "upper", "1", "-1"))
    for other in (before.replace(b'value="1"/>\n  <xacro:macro', b'value="2"/>\n  <xacro:macro'),
                  before.replace(b'xyz="0 0 1"', b'xyz="0 0 ${reach}"'),
                  before.replace(b'<axis xyz', b'<axes xyz'),
                  before.replace(b'<axis xyz="0 0 1"/>', b'<axis xyz="0 0 1"/><origin/>'),
                  before.replace(b'      <axis xyz="0 0 1"/>\n', b''),
                  before.replace(b'<child link="${side}_arm"/>', b'<child link="x"/>'),
                  before.replace(b'<parent link="${parent}"/>', b'<parent link="p"/>'),
                  before):
        assert literal_changes(before, other) is None


def _package(folder: Path) -> Path:
    (folder / "package.xml").write_text("<package format='3'><name>p</name></package>")
    (folder / "part.xacro").write_text(PART)
    top = folder / "robot.urdf.xacro"
    top.write_text(TOP)
    for path in folder.iterdir():
        os.utime(path, ns=(1_600_000_000 * 10**9,) * 2)
    return top


def test_a_changed_value_is_patched_into_every_element_written_at_its_line(
        tmp_path: Path) -> None:
    top = _package(tmp_path)
    expanded = expand_file(str(top), {})
    part = str(tmp_path / "part.xacro")
    change = (ValueChange(11, "xyz", "0 0 1", "0 1 0"),)
    patched = patch_document(expanded.xml, expanded.files, part, change)
    assert patched is not None and patched.count(b'xyz="0 1 0"') == 2  # both arms
    wrong = (ValueChange(11, "xyz", "1 1 1", "0 1 0"),)  # not the value the document holds
    assert patch_document(expanded.xml, expanded.files, part, wrong) is None


def test_a_save_that_changes_a_value_is_linted_without_expanding(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", str(tmp_path / "cache"))
    top = _package(tmp_path)
    part = top.parent / "part.xacro"
    session = Session()
    assert session.lint(str(part))[str(part)] == []
    part.write_text(PART.replace('lower="-1" upper="1"', 'lower="1" upper="-1"'))
    expand = driver.expand_file

    def refuse(*args: object, **kwargs: object) -> None:
        raise AssertionError("expanded again for a changed value")

    monkeypatch.setattr(driver, "expand_file", refuse)
    found = session.lint(str(part))[str(part)]
    assert sorted(d.element for d in found if d.code == "J103") == [
        "joint:left_shoulder", "joint:right_shoulder"]
    monkeypatch.setattr(driver, "expand_file", expand)
    fresh = Session().lint(str(part))[str(part)]  # a full expansion gives the same
    assert [(d.code, d.element, d.message, d.where) for d in found] == \
        [(d.code, d.element, d.message, d.where) for d in fresh]


def test_a_structural_change_expands_again(tmp_path: Path,
                                           monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", str(tmp_path / "cache"))
    top = _package(tmp_path)
    part = top.parent / "part.xacro"
    session = Session()
    session.lint(str(part))
    part.write_text(PART.replace('value="1"/>', 'value="2"/>', 1))  # a property: expand
    calls = []
    expand = driver.expand_file
    monkeypatch.setattr(driver, "expand_file", lambda *a, **k: calls.append(1) or expand(*a, **k))
    session.lint(str(part))
    assert calls


def test_config_targets_that_differ_only_in_their_args_are_kept_apart(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The Engineer's three targets have no matrix variant, only different `args`."""
    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", str(tmp_path / "cache"))
    top = _package(tmp_path)
    (tmp_path / "robotdesc.toml").write_text(
        '[[targets]]\nfile = "robot.urdf.xacro"\n\n'
        '[[targets]]\nfile = "robot.urdf.xacro"\nargs = { extra = "1" }\n')
    top.write_text(TOP.replace('<xacro:include', '<xacro:arg name="extra" default="0"/>\n'
                               '  <xacro:include'))
    session = Session()
    session.lint(str(tmp_path / "part.xacro"))
    assert sorted(args for _, args in session.results) == [(), (("extra", "1"),)]
