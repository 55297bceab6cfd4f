"""Suggested blocks and the unified diff against the sources (never written in place)."""

from __future__ import annotations

from pathlib import Path

from robotdesc.edit.index import ExpandedIndex
from robotdesc.edit.locate import SourceCache
from robotdesc.inertia.patch import build_patch
from robotdesc.inertia.suggest import format_inertial, suggest_inertial
from robotdesc.mesh.primitives import box_properties
from robotdesc.model.parse import parse_urdf

URDF = """<?xml version="1.0"?>
<robot name="r">
  <link name="base"/>
  <link name="arm">
    <inertial>
      <mass value="2"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
  </link>
  <link name="hand">
  </link>
  <link name="tip"/>
</robot>
"""


def _index(path: Path) -> ExpandedIndex:
    return ExpandedIndex(path.read_bytes(), str(path), ())


def test_block_is_plain_urdf_in_link_axes() -> None:
    block = format_inertial(box_properties(0.1, 0.2, 0.4).scaled_to_mass(2.0))
    assert block.splitlines() == [
        "<inertial>", '  <origin xyz="0 0 0" rpy="0 0 0"/>', '  <mass value="2"/>',
        ('  <inertia ixx="0.0333333" ixy="0" ixz="0" iyy="0.0283333" iyz="0" '
         'izz="0.00833333"/>'), "</inertial>"]


def test_patch_replaces_and_adds_blocks_without_touching_the_file(tmp_path: Path) -> None:
    path = tmp_path / "r.urdf"
    path.write_text(URDF)
    robot = parse_urdf(path.read_bytes(), str(path))
    box = box_properties(0.1, 0.2, 0.4)
    suggestions = [suggest_inertial(robot.link(n), box) for n in ("arm", "hand", "tip")]
    assert suggestions[0].replaces.line == 5 and suggestions[1].replaces is None
    assert "guessed" in suggestions[1].block  # no declared mass: says so
    patch = build_patch(suggestions, _index(path), SourceCache(str(tmp_path)),
                        relative_to=str(tmp_path))
    assert path.read_text() == URDF
    assert patch.diff.startswith("--- a/r.urdf\n+++ b/r.urdf\n")
    assert '-      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>' in patch.diff
    assert '+      <origin xyz="0 0 0" rpy="0 0 0"/>' in patch.diff
    assert '-  <link name="tip"/>' in patch.diff and '+  <link name="tip">' in patch.diff
    assert len(patch.changed) == 3 and patch.skipped == ()


def test_xacro_expressions_are_left_for_a_hand_edit(tmp_path: Path) -> None:
    path = tmp_path / "r.urdf"
    path.write_text(URDF.replace('ixx="1"', 'ixx="${2 * half}"'))
    robot = parse_urdf(URDF.encode(), str(path))
    patch = build_patch([suggest_inertial(robot.link("arm"), box_properties(1, 1, 1))],
                        ExpandedIndex(URDF.encode(), str(path), ()), SourceCache(str(tmp_path)))
    assert patch.diff == ""
    assert patch.skipped[0][1] == "computed at r.urdf:7: the expression '${2 * half}'"
