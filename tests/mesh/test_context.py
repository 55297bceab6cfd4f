"""MeshContext: package resolution without fallback, per-link geometry, memoisation."""

from __future__ import annotations

from pathlib import Path

import pytest

from robotdesc.mesh.context import MeshContext
from robotdesc.mesh.settings import MeshSettings
from robotdesc.model.parse import parse_urdf

from .builders import box_triangles, write_binary_stl

URDF = """<?xml version="1.0"?>
<robot name="r">
  <link name="a">
    <visual><origin xyz="0 0 1"/><geometry><mesh filename="package://pkg/box.stl"/></geometry></visual>
    <collision><geometry><box size="1 1 1"/></geometry></collision>
  </link>
  <link name="b">
    <visual><geometry><mesh filename="package://other/box.stl"/></geometry></visual>
  </link>
</robot>
"""


@pytest.fixture
def context(tmp_path: Path) -> MeshContext:
    (tmp_path / "pkg").mkdir()
    (tmp_path / "twin").mkdir()
    write_binary_stl(tmp_path / "pkg" / "box.stl", box_triangles((1.0, 2.0, 3.0)))
    write_binary_stl(tmp_path / "twin" / "box.stl", box_triangles())  # same relative path
    robot = parse_urdf(URDF.encode(), str(tmp_path / "r.urdf"))
    return MeshContext(robot, MeshSettings(cache=False), {"pkg": str(tmp_path / "pkg")}.get)


def test_unknown_package_is_a_problem_never_a_fallback(context: MeshContext) -> None:
    link = context.robot.link("b")
    found = context.lookup(link.visuals[0].geometry)
    assert found.summary is None and found.resolution.problem.kind.value == "unknown-package"


def test_collision_is_the_default_source_and_visual_is_an_option(context: MeshContext) -> None:
    link = context.robot.link("a")
    collision = context.link_geometry(link)
    assert collision.source == "collision" and collision.properties.volume == pytest.approx(1.0)
    visual = context.link_geometry(link, "visual")
    assert visual.source == "visual" and visual.properties.volume == pytest.approx(6.0)
    assert visual.properties.center_of_mass == pytest.approx((0, 0, 1))
    assert visual.bounds == (pytest.approx((-0.5, -1, -0.5)), pytest.approx((0.5, 1, 2.5)))


def test_link_without_the_configured_source_says_which_was_used(context: MeshContext) -> None:
    geometry = context.link_geometry(context.robot.link("b"))
    assert geometry.source == "visual" and "no collision geometry" in geometry.notes[0]
    assert not geometry.complete and "unknown package 'other'" in geometry.unmeasured[0]


def test_lookups_are_remembered(context: MeshContext) -> None:
    ref = context.robot.link("a").visuals[0].geometry
    assert context.lookup(ref) is context.lookup(ref)


def test_find_package_is_public_and_never_falls_back(context: MeshContext, tmp_path: Path) -> None:
    assert context.find_package("pkg") == str(tmp_path / "pkg")
    assert context.find_package("twin") is None


def test_a_link_of_primitives_is_measured_once_per_link_object(tmp_path: Path) -> None:
    """The variants of a description and an editor's saves share unchanged links (the
    model's parse): a link without meshes is measured once; a link with a mesh is measured
    per context (its file may have changed)."""
    robot = parse_urdf(URDF.replace('<mesh filename="package://other/box.stl"/>',
                                    '<cylinder radius="0.1" length="0.2"/>').encode(),
                       str(tmp_path / "r.urdf"))
    (tmp_path / "pkg").mkdir()
    stl = tmp_path / "pkg" / "box.stl"
    write_binary_stl(stl, box_triangles((1.0, 2.0, 3.0)))
    first, second = (MeshContext(robot, MeshSettings(cache=False), {"pkg": str(tmp_path / "pkg")}.get)
                     for _ in range(2))
    wheel, body = robot.link("b"), robot.link("a")
    assert second.link_geometry(wheel) is first.link_geometry(wheel)
    before = first.link_geometry(body, "visual")
    write_binary_stl(stl, box_triangles((1.0, 1.0, 1.0)))
    after = MeshContext(robot, MeshSettings(cache=False), {"pkg": str(tmp_path / "pkg")}.get) \
        .link_geometry(body, "visual")
    assert before.properties.volume == pytest.approx(6.0)
    assert after.properties.volume == pytest.approx(1.0)
