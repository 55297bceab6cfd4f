"""The mesh summary cache: location, round trip, corruption, and warm runs doing no work."""

from __future__ import annotations

from pathlib import Path

import pytest

from robotdesc.mesh import load as load_module
from robotdesc.mesh.analyze import analyze_mesh_file
from robotdesc.mesh.cache import MeshCache, default_cache_dir, summary_from_json, summary_to_json
from robotdesc.mesh.validate import MeshError, MeshErrorKind

from .builders import box_triangles, write_binary_stl


@pytest.mark.parametrize("env, expected", [
    ({"ROBOTDESC_CACHE_DIR": "/c/rd"}, Path("/c/rd")),
    ({"ROBOTDESC_CACHE_DIR": "off", "XDG_CACHE_HOME": "/x"}, None),
    ({"ROBOTDESC_CACHE_DIR": ""}, None),
    ({"XDG_CACHE_HOME": "/x", "HOME": "/h"}, Path("/x/robotdesc")),
    ({"HOME": "/h"}, Path("/h/.cache/robotdesc")),
])
def test_default_cache_dir(env, expected):
    assert default_cache_dir(env) == expected


@pytest.fixture
def mesh_file(tmp_path):
    return write_binary_stl(tmp_path / "box.stl", box_triangles())


def test_round_trip_is_exact(tmp_path, mesh_file):
    summary = analyze_mesh_file(mesh_file, scale=(0.1, 0.2, 0.3))
    assert summary_from_json(summary_to_json(summary)) == summary
    cache = MeshCache(tmp_path / "cache")
    key = cache.key_for(str(mesh_file), (0.1, 0.2, 0.3))
    cache.put(key, summary)
    assert cache.get(key) == summary
    assert not list((tmp_path / "cache").rglob(".tmp-*"))  # atomic writes leave no debris


def test_warm_run_does_no_mesh_work(tmp_path, mesh_file, monkeypatch):
    cache = MeshCache(tmp_path / "cache")
    cold = analyze_mesh_file(mesh_file, cache=cache)

    def fail(*args, **kwargs):
        raise AssertionError("the mesh was loaded again")

    monkeypatch.setattr(load_module, "load_mesh", fail)
    monkeypatch.setattr("robotdesc.mesh.cache.file_digest", fail)  # stat index hit: no hashing
    assert analyze_mesh_file(mesh_file, cache=cache) == cold


def test_scale_is_part_of_the_key(tmp_path, mesh_file):
    cache = MeshCache(tmp_path / "cache")
    one = analyze_mesh_file(mesh_file, cache=cache)
    two = analyze_mesh_file(mesh_file, scale=(2.0, 2.0, 2.0), cache=cache)
    assert two.properties.volume == pytest.approx(8 * one.properties.volume)


def test_changed_file_is_recomputed(tmp_path, mesh_file):
    cache = MeshCache(tmp_path / "cache")
    assert analyze_mesh_file(mesh_file, cache=cache).properties.volume == pytest.approx(6.0)
    write_binary_stl(mesh_file, box_triangles((2.0, 2.0, 2.0)))
    assert analyze_mesh_file(mesh_file, cache=cache).properties.volume == pytest.approx(8.0)


def test_corrupt_entries_are_ignored_and_rewritten(tmp_path, mesh_file):
    cache = MeshCache(tmp_path / "cache")
    good = analyze_mesh_file(mesh_file, cache=cache)
    for entry in (tmp_path / "cache").rglob("*.json"):
        entry.write_text('{"summary": {"properties": [1, 2')
    assert analyze_mesh_file(mesh_file, cache=cache) == good
    for entry in (tmp_path / "cache").rglob("*.json"):
        entry.write_text('{"summary": {"method": "bogus"}}')
    assert analyze_mesh_file(mesh_file, cache=cache) == good


def test_mesh_errors_are_cached(tmp_path, monkeypatch):
    path = tmp_path / "pointer.stl"
    path.write_text("version https://git-lfs.github.com/spec/v1\noid sha256:00\nsize 1\n")
    cache = MeshCache(tmp_path / "cache")
    with pytest.raises(MeshError):
        analyze_mesh_file(path, cache=cache)
    monkeypatch.setattr(load_module, "load_mesh", lambda *a, **k: pytest.fail("reloaded"))
    with pytest.raises(MeshError) as caught:
        analyze_mesh_file(path, cache=cache)
    assert caught.value.kind is MeshErrorKind.LFS_POINTER and "pointer.stl" in str(caught.value)


def test_unwritable_cache_is_not_an_error(tmp_path, mesh_file):
    blocker = tmp_path / "cache"
    blocker.write_text("a file where the cache directory should be")
    summary = analyze_mesh_file(mesh_file, cache=MeshCache(blocker))
    assert summary.properties.volume == pytest.approx(6.0)


def test_a_cache_is_empty_until_a_summary_is_stored(tmp_path, mesh_file):
    cache = MeshCache(tmp_path / "cache")
    assert cache.is_empty()  # not even created
    analyze_mesh_file(mesh_file, cache=cache)
    assert not cache.is_empty()
