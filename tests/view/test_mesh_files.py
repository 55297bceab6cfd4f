"""Mesh references resolved for display as the rules resolve them."""

from __future__ import annotations

from pathlib import Path

import robotdesc
from robotdesc.model.elements import MeshRef
from robotdesc.view.mesh_files import MeshFiles

from .robots import write_demo_package


def test_package_and_relative_references(tmp_path: Path) -> None:
    urdf = write_demo_package(tmp_path)
    files = MeshFiles.for_robot(robotdesc.load(str(urdf)))
    found = files.resolve(MeshRef("package://demo/meshes/block.stl"))
    assert found.ok and Path(found.path).name == "block.stl"
    relative = files.resolve(MeshRef("../meshes/block.stl"))
    assert relative.ok and relative.path == found.path
    escaping = files.resolve(MeshRef("../../outside.stl"))
    assert not escaping.ok


def test_unknown_package_and_absolute_paths(tmp_path: Path) -> None:
    urdf = write_demo_package(tmp_path)
    robot = robotdesc.load(str(urdf))
    mesh = str(tmp_path / "demo" / "meshes" / "block.stl")
    assert "unknown package" in MeshFiles.for_robot(robot).resolve(
        MeshRef("package://nope/a.stl")).problem.message
    assert not MeshFiles.for_robot(robot).resolve(MeshRef(mesh)).ok
    assert MeshFiles.for_robot(robot, allow_absolute=True).resolve(MeshRef(mesh)).ok
