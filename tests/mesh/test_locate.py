"""MeshLocator: the one rule for where a `<mesh filename>` leads (package lookup, the folder of
the file that wrote the element, the package root, the absolute-path policy, symlinks)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from robotdesc.mesh.context import MeshContext
from robotdesc.mesh.locate import MeshLocator
from robotdesc.mesh.resolve import ResolveProblemKind
from robotdesc.mesh.settings import MeshSettings
from robotdesc.model.elements import MeshRef, Robot
from robotdesc.source import Provenance, Span

from .builders import box_triangles, write_binary_stl


@pytest.fixture
def package(tmp_path: Path) -> Path:
    """demo/ (a package): urdf/robot.urdf, urdf/parts/part.xacro, meshes/block.stl,
    urdf/parts/meshes/part.stl; and outside.stl next to the package."""
    root = tmp_path / "demo"
    (root / "urdf" / "parts" / "meshes").mkdir(parents=True)
    (root / "meshes").mkdir()
    (root / "package.xml").write_text("<package><name>demo</name></package>")
    (root / "urdf" / "robot.urdf").write_text("<robot name='r'/>")
    (root / "urdf" / "parts" / "part.xacro").write_text("<robot/>")
    write_binary_stl(root / "meshes" / "block.stl", box_triangles())
    write_binary_stl(root / "urdf" / "parts" / "meshes" / "part.stl", box_triangles())
    write_binary_stl(tmp_path / "outside.stl", box_triangles())
    return root


def _robot(package: Path) -> Robot:
    return Robot("r", source=str(package / "urdf" / "robot.urdf"))


def _written_in(filename: str, path: Path | str) -> MeshRef:
    return MeshRef(filename, where=Provenance(Span(str(path), 3, 5)))


def test_package_and_relative_references(package: Path) -> None:
    locator = MeshLocator.for_robot(_robot(package))
    found = locator.locate(MeshRef("package://demo/meshes/block.stl"))
    assert found.ok and found.path == os.path.realpath(package / "meshes" / "block.stl")
    relative = locator.locate(MeshRef("../meshes/block.stl"))  # from robot.source's folder
    assert relative.ok and relative.path == found.path
    assert locator.path(MeshRef("../meshes/block.stl")) == found.path
    escaping = locator.locate(MeshRef("../../outside.stl"))
    assert escaping.problem is not None
    assert escaping.problem.kind is ResolveProblemKind.ESCAPES_ROOT


def test_relative_paths_start_at_the_file_that_wrote_the_element(package: Path) -> None:
    locator = MeshLocator(_robot(package), lambda name: None)
    part = package / "urdf" / "parts" / "part.xacro"
    ref = _written_in("meshes/part.stl", part)
    assert locator.base_dir(ref) == str(part.parent)
    found = locator.locate(ref)
    assert found.ok and found.path == os.path.realpath(part.parent / "meshes" / "part.stl")
    # the same text written in the top file means another (missing) file
    top = _written_in("meshes/part.stl", package / "urdf" / "robot.urdf")
    missing = locator.locate(top)
    assert missing.problem is not None and missing.problem.kind is ResolveProblemKind.MISSING


def test_an_unknown_writer_falls_back_to_the_source_then_the_cwd(
        package: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    locator = MeshLocator(_robot(package), lambda name: None)
    gone = _written_in("x.stl", package / "no" / "such.xacro")
    assert locator.base_dir(gone) == str(package / "urdf")
    assert locator.base_dir(MeshRef("x.stl")) == str(package / "urdf")
    monkeypatch.chdir(package / "meshes")
    assert MeshLocator(Robot("r"), lambda name: None).base_dir(MeshRef("x.stl")) == str(
        package / "meshes")
    assert MeshLocator(Robot("r"), lambda name: None).locate(MeshRef("block.stl")).ok


def test_absolute_paths_and_file_uris_only_when_the_policy_allows(package: Path) -> None:
    robot = _robot(package)
    mesh = str(package / "meshes" / "block.stl")
    for filename in (mesh, "file://" + mesh):
        refused = MeshLocator.for_robot(robot).locate(MeshRef(filename))
        assert refused.problem is not None
        assert refused.problem.kind is ResolveProblemKind.ABSOLUTE_NOT_ALLOWED
        assert MeshLocator.for_robot(robot, allow_absolute=True).locate(MeshRef(filename)).ok
    allowed = MeshLocator.with_settings(robot, lambda name: None,
                                        MeshSettings(allow_absolute_paths=True))
    assert allowed.allow_absolute and allowed.locate(MeshRef(mesh)).ok
    assert not MeshLocator.with_settings(robot, lambda name: None,
                                         MeshSettings()).allow_absolute


def test_unknown_package_is_a_problem_never_a_fallback(package: Path) -> None:
    found = MeshLocator.for_robot(_robot(package)).locate(MeshRef("package://nope/a.stl"))
    assert found.problem is not None and "unknown package 'nope'" in found.problem.message


def test_symlinks_are_followed_and_held_to_the_package_root(package: Path) -> None:
    os.symlink(package / "meshes" / "block.stl", package / "urdf" / "alias.stl")
    os.symlink(package.parent / "outside.stl", package / "urdf" / "leak.stl")
    locator = MeshLocator.for_robot(_robot(package))
    alias = locator.locate(MeshRef("alias.stl"))
    assert alias.path == os.path.realpath(package / "meshes" / "block.stl")
    leak = locator.locate(MeshRef("leak.stl"))
    assert leak.problem is not None and leak.problem.kind is ResolveProblemKind.ESCAPES_ROOT


def test_outside_any_package_relative_paths_are_not_confined(tmp_path: Path) -> None:
    (tmp_path / "robot").mkdir()
    write_binary_stl(tmp_path / "shared.stl", box_triangles())
    robot = Robot("r", source=str(tmp_path / "robot" / "r.urdf"))
    locator = MeshLocator(robot, lambda name: None)
    assert locator.package_root(str(tmp_path / "robot")) is None
    assert locator.locate(MeshRef("../shared.stl")).ok


def test_answers_are_remembered(package: Path) -> None:
    calls: list[str] = []

    def find(name: str) -> str | None:
        calls.append(name)
        return str(package)

    locator = MeshLocator(_robot(package), find)
    first = locator.locate(MeshRef("package://demo/meshes/block.stl"))
    assert locator.locate(MeshRef("package://demo/meshes/block.stl")) is first
    assert calls == ["demo"]


def test_the_rules_mesh_context_answers_through_its_locator(package: Path) -> None:
    robot = _robot(package)
    context = MeshContext(robot, MeshSettings(cache=False), {"demo": str(package)}.get)
    assert isinstance(context.locator, MeshLocator) and not context.locator.allow_absolute
    ref = _written_in("meshes/part.stl", package / "urdf" / "parts" / "part.xacro")
    found = context.lookup(ref)
    assert found.resolution == context.locator.locate(ref) and found.summary is not None
    mesh = str(package / "meshes" / "block.stl")
    assert context.lookup(MeshRef(mesh)).resolution.problem is not None
    allowing = MeshContext(robot, MeshSettings(cache=False, allow_absolute_paths=True),
                           lambda name: None)
    assert allowing.lookup(MeshRef(mesh)).resolution.ok
