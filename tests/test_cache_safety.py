"""Caches that cannot hang or lie, as a user meets them: an entry replaced by a FIFO, by a
symlink to /dev/zero, grown past its cap, or swapped with another key's entry is recomputed,
and the run gives what a clean run gives. ROBOTDESC_CACHE_DIR=off turns every cache off."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from mesh.builders import box_triangles, write_binary_stl

from robotdesc.cache_dir import cache_root, read_regular_file
from robotdesc.diagnostics import Finding
from robotdesc.expansion import ExpandOptions, expand_file
from robotdesc.linting import rule_cache
from robotdesc.mesh import cache as mesh_cache
from robotdesc.mesh.cache import MeshCache

TOP = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find demo)/urdf/parts.xacro"/>
  <xacro:part name="small" mesh="small.stl" size="0.1"/>
  <xacro:part name="large" mesh="large.stl" size="1.0"/>
  <joint name="j" type="fixed"><parent link="small"/><child link="large"/></joint>
</robot>
"""

# Each link's inertial is that of its own mesh at 1 kg: a swapped summary would not match.
PARTS = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part" params="name mesh size">
    <xacro:property name="i" value="${size * size / 6}"/>
    <link name="${name}">
      <inertial><mass value="1"/>
        <inertia ixx="${i}" iyy="${i}" izz="${i}" ixy="0" ixz="0" iyz="0"/></inertial>
      <visual><geometry><mesh filename="package://demo/meshes/${mesh}"/></geometry></visual>
      <collision><geometry><mesh filename="package://demo/meshes/${mesh}"/></geometry>
      </collision>
    </link>
  </xacro:macro>
</robot>
"""


@pytest.fixture
def package(tmp_path: Path) -> Path:
    root = tmp_path / "demo"
    for folder in ("urdf", "meshes"):
        (root / folder).mkdir(parents=True)
    (root / "package.xml").write_text("<package format='3'><name>demo</name></package>\n")
    (root / "urdf" / "robot.urdf.xacro").write_text(TOP)
    (root / "urdf" / "parts.xacro").write_text(PARTS)
    write_binary_stl(root / "meshes" / "small.stl", box_triangles((0.1, 0.1, 0.1)))
    write_binary_stl(root / "meshes" / "large.stl", box_triangles((1.0, 1.0, 1.0)))
    return root


def _lint(package: Path, cache: str, timeout: float = 120) -> tuple[int, list]:
    """`robotdesc lint --format json` in a child (a hang fails the test, never the suite)."""
    env = {**os.environ, "ROBOTDESC_CACHE_DIR": cache}
    done = subprocess.run([sys.executable, "-m", "robotdesc", "lint", "--format", "json",
                           str(package / "urdf" / "robot.urdf.xacro")],
                          capture_output=True, text=True, env=env, timeout=timeout,
                          cwd=package.parent)
    assert done.returncode in (0, 1), done.stderr
    report = json.loads(done.stdout)
    assert report["summary"]["files_checked"] == 1
    return done.returncode, [(d["code"], d["message"], d["line"])
                             for d in report["diagnostics"]]


def _entries(cache: Path) -> list[Path]:
    return sorted(p for p in cache.rglob("*.json") if p.is_file() and not p.is_symlink())


@pytest.fixture
def clean(package: Path) -> tuple[int, list]:
    """What a run without any cache gives."""
    return _lint(package, "off")


def test_entries_replaced_by_fifos_do_not_hang(package, clean, tmp_path):
    cache = tmp_path / "cache"
    assert _lint(package, str(cache)) == clean
    entries = _entries(cache)
    assert any("meshes-v" in str(p) for p in entries) and any("expand" in str(p)
                                                               for p in entries)
    for entry in entries:
        entry.unlink()
        os.mkfifo(entry)
    assert _lint(package, str(cache), timeout=60) == clean


def test_entries_replaced_by_a_symlink_to_dev_zero_are_not_read(package, clean, tmp_path):
    cache = tmp_path / "cache"
    assert _lint(package, str(cache)) == clean
    for entry in _entries(cache):
        entry.unlink()
        entry.symlink_to("/dev/zero")
    assert _lint(package, str(cache), timeout=60) == clean


def test_mesh_entries_swapped_between_keys_are_recomputed(package, clean, tmp_path):
    cache = tmp_path / "cache"
    assert _lint(package, str(cache)) == clean
    for kind in ("meshes-v", "stat-v"):
        found = [p for p in _entries(cache) if kind in str(p)]
        assert len(found) == 2, found
        first, second = (p.read_bytes() for p in found)
        found[0].write_bytes(second)
        found[1].write_bytes(first)
    assert _lint(package, str(cache)) == clean


def test_a_swapped_mesh_summary_is_not_used(package, tmp_path):
    meshes = MeshCache(tmp_path / "cache")
    small, large = (str(package / "meshes" / n) for n in ("small.stl", "large.stl"))
    from robotdesc.mesh.analyze import analyze_mesh_file

    keys = [meshes.key_for(path, (1.0, 1.0, 1.0)) for path in (small, large)]
    for path in (small, large):
        analyze_mesh_file(path, (1.0, 1.0, 1.0), cache=meshes)
    assert all(meshes.get(key) is not None for key in keys)
    entries = [tmp_path / "cache" / f"meshes-v{mesh_cache.CACHE_VERSION}" / k[:2] / f"{k}.json" for k in keys]
    first, second = (p.read_bytes() for p in entries)
    entries[0].write_bytes(second)
    entries[1].write_bytes(first)
    assert meshes.get(keys[0]) is None and meshes.get(keys[1]) is None


def test_expansion_entries_swapped_between_keys_are_recomputed(package, tmp_path):
    options = ExpandOptions(cache_dir=str(tmp_path / "cache"))
    other = package / "urdf" / "other.urdf.xacro"
    other.write_text(TOP.replace('name="r"', 'name="other"'))
    tops = [package / "urdf" / "robot.urdf.xacro", other]
    clean = [expand_file(str(t), options=ExpandOptions(use_cache=False)).xml for t in tops]
    assert [expand_file(str(t), options=options).xml for t in tops] == clean
    entries = sorted((tmp_path / "cache" / "expand").rglob("*.json"))
    assert len(entries) == 2
    first, second = (p.read_bytes() for p in entries)
    entries[0].write_bytes(second)
    entries[1].write_bytes(first)
    assert [expand_file(str(t), options=options).xml for t in tops] == clean


def test_rule_entries_swapped_between_keys_are_a_miss(tmp_path):
    one, two = [Finding("one", None, "link:a", None)], [Finding("two", None, "link:b", None)]
    rule_cache.store(tmp_path, "k1", one)
    rule_cache.store(tmp_path, "k2", two)
    assert rule_cache.load(tmp_path, "k1") == one
    first, second = (rule_cache.entry_path(tmp_path, k).read_bytes() for k in ("k1", "k2"))
    rule_cache.entry_path(tmp_path, "k1").write_bytes(second)
    assert rule_cache.load(tmp_path, "k1") is None
    rule_cache.entry_path(tmp_path, "k1").unlink()
    os.mkfifo(rule_cache.entry_path(tmp_path, "k1"))
    assert rule_cache.load(tmp_path, "k1") is None


def test_an_entry_beyond_its_cap_is_not_read(tmp_path):
    entry = tmp_path / "big.json"
    entry.write_bytes(b" " * 2048 + b"{}")
    assert read_regular_file(entry, 1024) is None
    assert read_regular_file(entry, 4096) == b" " * 2048 + b"{}"
    fifo = tmp_path / "fifo.json"
    os.mkfifo(fifo)
    assert read_regular_file(fifo, 1024) is None  # returns at once: no writer is awaited
    link = tmp_path / "zero.json"
    link.symlink_to("/dev/zero")
    assert read_regular_file(link, 1 << 40) is None


def test_cache_dir_off_turns_every_cache_off(package, tmp_path):
    assert cache_root({"ROBOTDESC_CACHE_DIR": "off"}) is None
    work = tmp_path / "work"
    work.mkdir()
    env = {**os.environ, "ROBOTDESC_CACHE_DIR": "off"}
    for command in (["lint"], ["expand"]):
        done = subprocess.run([sys.executable, "-m", "robotdesc", *command,
                               str(package / "urdf" / "robot.urdf.xacro")],
                              capture_output=True, env=env, cwd=work, timeout=120)
        assert done.returncode in (0, 1), done.stderr
    assert list(work.iterdir()) == []  # no folder named "off" (or anything else)
