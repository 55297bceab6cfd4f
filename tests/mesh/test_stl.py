"""The numpy STL reader: binary and ASCII, and refusal of broken or hostile files."""

from __future__ import annotations

import numpy as np
import pytest

from robotdesc.mesh.stl import read_stl
from robotdesc.mesh.validate import MeshError, MeshErrorKind, MeshLimits

from .builders import write_ascii_stl, write_binary_stl


def test_binary_round_trip(tmp_path, box_soup):
    path = write_binary_stl(tmp_path / "box.stl", box_soup)
    triangles = read_stl(path)
    assert triangles.shape == (12, 3, 3)
    np.testing.assert_array_equal(triangles, box_soup.astype(np.float32))


def test_binary_whose_header_starts_with_solid_is_read_as_binary(tmp_path, box_soup):
    path = write_binary_stl(tmp_path / "solid.stl", box_soup, header=b"solid exported by CAD")
    assert read_stl(path).shape == (12, 3, 3)


def test_ascii(tmp_path, box_soup):
    path = write_ascii_stl(tmp_path / "box.stl", box_soup * 1e-3)
    np.testing.assert_allclose(read_stl(path), box_soup * 1e-3, rtol=0, atol=1e-15)


def test_ascii_with_a_missing_vertex_is_malformed(tmp_path, box_soup):
    path = write_ascii_stl(tmp_path / "box.stl", box_soup)
    text = path.read_text().replace("vertex", "vortex", 1)
    path.write_text(text)
    with pytest.raises(MeshError) as caught:
        read_stl(path)
    assert caught.value.kind is MeshErrorKind.MALFORMED
    assert "12 facets but 35 vertices" in str(caught.value)


def test_truncated_binary(tmp_path, box_soup):
    path = write_binary_stl(tmp_path / "cut.stl", box_soup)
    path.write_bytes(path.read_bytes()[:-30])
    with pytest.raises(MeshError) as caught:
        read_stl(path)
    assert caught.value.kind is MeshErrorKind.TRUNCATED
    assert "claims 12 triangles" in str(caught.value) and "cut.stl" in str(caught.value)


def test_header_claiming_2_pow_31_triangles_allocates_nothing(tmp_path, box_soup):
    path = write_binary_stl(tmp_path / "liar.stl", box_soup, count=2 ** 31)
    with pytest.raises(MeshError) as caught:
        read_stl(path)
    assert caught.value.kind is MeshErrorKind.TRUNCATED
    assert "2147483648" in str(caught.value)


def test_nan_vertices(tmp_path, box_soup):
    soup = box_soup.copy()
    soup[3, 1, 2] = np.nan
    path = write_binary_stl(tmp_path / "nan.stl", soup)
    with pytest.raises(MeshError) as caught:
        read_stl(path)
    assert caught.value.kind is MeshErrorKind.NON_FINITE


def test_lfs_pointer(tmp_path):
    path = tmp_path / "part.stl"
    path.write_text("version https://git-lfs.github.com/spec/v1\n"
                    "oid sha256:4d7a214614ab2935c943f9e0ff69d22eadbb8f32b1258daaa5e2ca24d17e2393\n"
                    "size 12345\n")
    with pytest.raises(MeshError) as caught:
        read_stl(path)
    assert caught.value.kind is MeshErrorKind.LFS_POINTER
    assert "git lfs pull" in str(caught.value)


def test_empty_file(tmp_path):
    path = tmp_path / "empty.stl"
    path.write_bytes(b"")
    with pytest.raises(MeshError) as caught:
        read_stl(path)
    assert caught.value.kind is MeshErrorKind.EMPTY


def test_size_limit_is_checked_before_reading(tmp_path, box_soup):
    path = write_binary_stl(tmp_path / "box.stl", np.concatenate([box_soup] * 10))
    with pytest.raises(MeshError) as caught:
        read_stl(path, MeshLimits(max_file_bytes=1000))
    assert caught.value.kind is MeshErrorKind.TOO_LARGE
    with pytest.raises(MeshError) as caught:
        read_stl(path, MeshLimits(max_triangles=100))
    assert "120 triangles" in str(caught.value)


def test_agrees_with_trimesh_on_a_real_mesh(robots_dir):
    trimesh = pytest.importorskip("trimesh")
    path = robots_dir / "talos_data/meshes/arm/arm_7_collision.STL"
    ours = read_stl(path)
    theirs = trimesh.load(path, process=False)
    np.testing.assert_allclose(ours, theirs.triangles, rtol=0, atol=1e-7)


def test_ascii_real_mesh_agrees_with_trimesh(robots_dir):
    trimesh = pytest.importorskip("trimesh")
    ascii_files = [p for p in sorted(robots_dir.rglob("*.stl")) + sorted(robots_dir.rglob("*.STL"))
                   if p.read_bytes()[:5].lower() == b"solid" and not _binary_size(p)]
    if not ascii_files:
        pytest.skip("no ASCII STL in example-robot-data")
    ours = read_stl(ascii_files[0])
    theirs = trimesh.load(ascii_files[0], process=False)
    assert ours.shape == theirs.triangles.shape
    np.testing.assert_allclose(ours, theirs.triangles, rtol=1e-6, atol=1e-9)


def _binary_size(path) -> bool:
    head = path.read_bytes()[:84]
    return path.stat().st_size == 84 + 50 * int.from_bytes(head[80:84], "little")
