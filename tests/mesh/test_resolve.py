"""Resolving `<mesh filename>` references: problems are values, never exceptions."""

from __future__ import annotations

import os

import pytest

from robotdesc.mesh.resolve import ResolveProblemKind, find_case_insensitive, resolve_mesh


@pytest.fixture
def workspace(tmp_path):
    """Two packages: engineer_description (with meshes) and other_description."""
    engineer = tmp_path / "src/engineer_description"
    (engineer / "meshes").mkdir(parents=True)
    (engineer / "urdf").mkdir()
    (engineer / "meshes/base.stl").write_bytes(b"x")
    (engineer / "meshes/Cronstain.dae").write_text("<COLLADA/>")
    other = tmp_path / "src/other_description"
    (other / "meshes").mkdir(parents=True)
    (other / "meshes/wheel.stl").write_bytes(b"x")
    (tmp_path / "secret.stl").write_bytes(b"x")
    packages = {"engineer_description": str(engineer), "other_description": str(other)}
    return tmp_path, engineer, packages.get


def _resolve(workspace, filename, **options):
    _, engineer, lookup = workspace
    return resolve_mesh(filename, base_dir=str(engineer / "urdf"), find_package=lookup,
                        **options)


def test_package_uri(workspace):
    _, engineer, _ = workspace
    found = _resolve(workspace, "package://engineer_description/meshes/base.stl")
    assert found.ok and found.problem is None and found.warnings == ()
    assert found.path == os.path.realpath(engineer / "meshes/base.stl")
    assert found.package == "engineer_description"


def test_three_slashes_accepted_with_a_warning(workspace):
    found = _resolve(workspace, "package:///engineer_description/meshes/base.stl")
    assert found.ok
    assert "three slashes" in found.warnings[0]


def test_unknown_package_never_falls_back(workspace):
    found = _resolve(workspace, "package://engineer_bringup/meshes/wheel.stl")
    assert not found.ok
    assert found.problem.kind is ResolveProblemKind.UNKNOWN_PACKAGE
    assert "engineer_bringup" in found.problem.message


def test_file_of_another_package_is_not_found_in_this_one(workspace):
    found = _resolve(workspace, "package://engineer_description/meshes/wheel.stl")
    assert found.problem.kind is ResolveProblemKind.MISSING


def test_dotdot_escaping_the_package(workspace):
    found = _resolve(workspace, "package://engineer_description/../../secret.stl")
    assert found.problem.kind is ResolveProblemKind.ESCAPES_ROOT
    assert "outside its package root" in found.problem.message


def test_symlink_leading_out_of_the_package(workspace):
    root, engineer, _ = workspace
    os.symlink(root / "secret.stl", engineer / "meshes/link.stl")
    found = _resolve(workspace, "package://engineer_description/meshes/link.stl")
    assert found.problem.kind is ResolveProblemKind.ESCAPES_ROOT


def test_symlink_inside_the_package_is_fine(workspace):
    _, engineer, _ = workspace
    os.symlink(engineer / "meshes/base.stl", engineer / "meshes/alias.stl")
    assert _resolve(workspace, "package://engineer_description/meshes/alias.stl").ok


def test_case_mismatch_names_the_existing_file(workspace):
    _, engineer, _ = workspace
    found = _resolve(workspace, "package://engineer_description/meshes/cronstain.dae")
    assert found.problem.kind is ResolveProblemKind.CASE_MISMATCH
    assert found.problem.candidate == str(engineer / "meshes/Cronstain.dae")
    assert "'Cronstain.dae' does" in found.problem.message


def test_case_mismatch_in_a_directory_name(workspace):
    found = _resolve(workspace, "package://engineer_description/Meshes/base.stl")
    assert found.problem.kind is ResolveProblemKind.CASE_MISMATCH


def test_missing_file(workspace):
    found = _resolve(workspace, "package://engineer_description/meshes/nothing.stl")
    assert found.problem.kind is ResolveProblemKind.MISSING


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this platform")
def test_fifo_is_not_a_regular_file(workspace):
    _, engineer, _ = workspace
    os.mkfifo(engineer / "meshes/pipe.stl")
    found = _resolve(workspace, "package://engineer_description/meshes/pipe.stl")
    assert found.problem.kind is ResolveProblemKind.NOT_REGULAR_FILE
    assert "FIFO" in found.problem.message


def test_directory_is_not_a_regular_file(workspace):
    found = _resolve(workspace, "package://engineer_description/meshes")
    assert found.problem.kind is ResolveProblemKind.NOT_REGULAR_FILE


def test_device_is_not_a_regular_file(workspace):
    if not os.path.exists("/dev/null"):
        pytest.skip("no /dev/null")
    found = _resolve(workspace, "/dev/null", allow_absolute=True)
    assert found.problem.kind is ResolveProblemKind.NOT_REGULAR_FILE
    assert "device" in found.problem.message


def test_relative_path_from_the_urdf_directory(workspace):
    _, engineer, _ = workspace
    found = _resolve(workspace, "../meshes/base.stl", relative_root=str(engineer))
    assert found.path == os.path.realpath(engineer / "meshes/base.stl")


def test_relative_path_escaping_its_root(workspace):
    _, engineer, _ = workspace
    found = _resolve(workspace, "../../../secret.stl", relative_root=str(engineer))
    assert found.problem.kind is ResolveProblemKind.ESCAPES_ROOT


@pytest.mark.parametrize("spelling", ["absolute", "file"])
def test_absolute_and_file_uri_refused_unless_allowed(workspace, spelling):
    root, _, _ = workspace
    target = str(root / "secret.stl")
    filename = target if spelling == "absolute" else "file://" + target
    refused = _resolve(workspace, filename)
    assert refused.problem.kind is ResolveProblemKind.ABSOLUTE_NOT_ALLOWED
    allowed = _resolve(workspace, filename, allow_absolute=True)
    assert allowed.path == os.path.realpath(target)


@pytest.mark.parametrize("filename, kind", [
    ("", ResolveProblemKind.EMPTY),
    ("package://", ResolveProblemKind.EMPTY),
    ("package://engineer_description", ResolveProblemKind.EMPTY),
    ("http://example.com/base.stl", ResolveProblemKind.UNSUPPORTED_SCHEME),
])
def test_unusable_spellings(workspace, filename, kind):
    assert _resolve(workspace, filename).problem.kind is kind


def test_case_insensitive_search_refuses_ambiguity(tmp_path):
    (tmp_path / "A.stl").write_bytes(b"")
    (tmp_path / "a.STL").write_bytes(b"")
    assert find_case_insensitive(str(tmp_path / "a.stl"), str(tmp_path)) is None
