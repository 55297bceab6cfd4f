"""Fixes that are right: a mesh in millimetres is scaled before its inertia is suggested, a
g*mm^2 tensor gets the kg*m^2 one, and a rotated tensor (right moments, wrong axes) is listed
by `inertia --suggest` without `--all`, so `--write` patches every wrong link."""

from __future__ import annotations

from pathlib import Path

import pytest
from mesh.builders import box_triangles, write_binary_stl

from robotdesc.inertia.suggest import select_suggestions, suggest_for_link
from robotdesc.mesh.context import MeshContext
from robotdesc.mesh.settings import MeshSettings
from robotdesc.model.parse import parse_urdf

SETTINGS = MeshSettings(cache=False)
BOX = 'ixx="0.0166667" ixy="0" ixz="0" iyy="0.0141667" iyz="0" izz="0.00416667"'


def _link(name: str, inertia: str, mesh: str) -> str:
    return (f'<link name="{name}"><inertial><mass value="1"/><inertia {inertia}/></inertial>'
            f'<collision><geometry><mesh filename="package://pkg/meshes/{mesh}"/></geometry>'
            f'</collision></link>')


@pytest.fixture()
def robot_and_meshes(tmp_path: Path):
    meshes = tmp_path / "pkg" / "meshes"
    meshes.mkdir(parents=True)
    (tmp_path / "pkg" / "package.xml").write_text("<package><name>pkg</name></package>")
    box = box_triangles((0.1, 0.2, 0.4))
    write_binary_stl(meshes / "box.stl", box)
    write_binary_stl(meshes / "box_mm.stl", box * 1000)
    links = [_link("good", BOX, "box.stl"),
             _link("grams_mm2", 'ixx="16666700" ixy="0" ixz="0" iyy="14166700" iyz="0" '
                   'izz="4166670"', "box.stl"),
             _link("rotated", 'ixx="0.00416667" ixy="0" ixz="0" iyy="0.0141667" iyz="0" '
                   'izz="0.0166667"', "box.stl"),
             _link("millimetres", BOX, "box_mm.stl")]
    joints = "".join(f'<joint name="j_{n}" type="continuous"><parent link="base"/>'
                     f'<child link="{n}"/><origin xyz="0 0 {i * 0.5}"/></joint>'
                     for i, n in enumerate(("good", "grams_mm2", "rotated", "millimetres")))
    text = f'<robot name="r"><link name="base"/>{"".join(links)}{joints}</robot>'
    urdf = tmp_path / "pkg" / "r.urdf"
    urdf.write_text(text)
    robot = parse_urdf(text.encode(), str(urdf))
    packages = {"pkg": str(tmp_path / "pkg")}
    return robot, MeshContext(robot, SETTINGS, packages.get)


def test_millimetre_mesh_suggestion_is_that_of_the_scaled_mesh(robot_and_meshes) -> None:
    robot, meshes = robot_and_meshes
    block = suggest_for_link(robot, meshes, robot.link("millimetres")).block
    assert 'ixx="0.0166667"' in block and 'izz="0.00416667"' in block  # not 1e6 times that
    assert 'scale="0.001 0.001 0.001"' in block


def test_grams_mm2_tensor_gets_the_kg_m2_one(robot_and_meshes) -> None:
    robot, meshes = robot_and_meshes
    block = suggest_for_link(robot, meshes, robot.link("grams_mm2")).block
    assert 'ixx="0.0166667"' in block and '<mass value="1"/>' in block


def test_suggest_lists_every_wrong_link_including_a_rotated_tensor(robot_and_meshes) -> None:
    robot, meshes = robot_and_meshes
    chosen = {s.link for s in select_suggestions(robot, meshes)}
    assert chosen == {"grams_mm2", "rotated", "millimetres"}
    rotated = next(s for s in select_suggestions(robot, meshes) if s.link == "rotated")
    assert 'ixx="0.0166667"' in rotated.block and 'izz="0.00416667"' in rotated.block
    assert {s.link for s in select_suggestions(robot, meshes, everything=True)} == \
        {"good", "grams_mm2", "rotated", "millimetres"}
