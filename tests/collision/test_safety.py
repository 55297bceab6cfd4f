"""`robotdesc collision` as a hostile folder meets it: --out that is a file or read-only is
exit 2; a manifest naming `../x` or an absolute path never deletes it; a mesh reached through
a symlink, `../` or file:// out of its package is a finding, never read; nothing is written
outside --out."""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest
from mesh.builders import box_triangles, write_binary_stl

from robotdesc.cli import main
from robotdesc.collision.manifest import MANIFEST_NAME
from robotdesc.digest import file_digest


@pytest.fixture
def package(tmp_path: Path) -> Path:
    """A package `demo` with two box meshes."""
    root = tmp_path / "demo"
    (root / "meshes").mkdir(parents=True)
    (root / "urdf").mkdir()
    (root / "package.xml").write_text("<package format='3'><name>demo</name></package>")
    write_binary_stl(root / "meshes" / "a.stl", box_triangles((0.1, 0.2, 0.3)))
    write_binary_stl(root / "meshes" / "b.stl", box_triangles((0.3, 0.2, 0.1)))
    return root


def _urdf(root: Path, meshes: dict[str, str]) -> Path:
    links = "".join(f'<link name="{name}"><visual><geometry><mesh filename="{mesh}"/>'
                    f"</geometry></visual></link>" for name, mesh in meshes.items())
    names = list(meshes)
    joints = "".join(f'<joint name="j{i}" type="fixed"><parent link="{a}"/>'
                     f'<child link="{b}"/></joint>' for i, (a, b) in enumerate(zip(names,
                                                                                  names[1:])))
    path = root / "urdf" / "demo.urdf"
    path.write_text(f'<?xml version="1.0"?>\n<robot name="demo">{links}{joints}</robot>\n')
    return path


def _collision(urdf: Path, out: Path, *extra: str) -> int:
    return main(["collision", str(urdf), "--method", "hull", "--out", str(out), "-j", "1",
                 *extra])


@contextlib.contextmanager
def _read_only(folder: Path):
    """A folder nobody can write in (root too: the immutable flag)."""
    if os.geteuid() == 0:
        if shutil.which("chattr") is None or subprocess.run(
                ["chattr", "+i", str(folder)], capture_output=True).returncode != 0:
            pytest.skip("cannot make a read-only folder as root here")
        try:
            yield
        finally:
            subprocess.run(["chattr", "-i", str(folder)], check=True)
    else:
        folder.chmod(0o555)
        try:
            yield
        finally:
            folder.chmod(0o755)


def test_out_that_is_a_file_is_exit_2(package, capsys):
    urdf = _urdf(package, {"a": "package://demo/meshes/a.stl"})
    out = package.parent / "out"
    out.write_text("not a folder")
    assert _collision(urdf, out) == 2
    assert "is a file, not a folder" in capsys.readouterr().err
    assert out.read_text() == "not a folder"
    assert _collision(urdf, out / "sub") == 2


def test_read_only_out_is_exit_2(package, capsys):
    urdf = _urdf(package, {"a": "package://demo/meshes/a.stl"})
    out = package.parent / "out"
    out.mkdir()
    with _read_only(out):
        assert _collision(urdf, out) == 2
        assert "read-only" in capsys.readouterr().err
        assert _collision(urdf, out / "sub") == 2
    assert list(out.iterdir()) == []


def test_manifest_entries_outside_out_are_never_deleted(package, capsys):
    urdf = _urdf(package, {"a": "package://demo/meshes/a.stl"})
    out = package.parent / "out"
    assert _collision(urdf, out) == 0
    beside = package.parent / "beside.txt"
    beside.write_text("keep me")
    source = package / "meshes" / "b.stl"
    manifest = json.loads((out / MANIFEST_NAME).read_text())
    beside_digest, source_digest = file_digest(str(beside)), file_digest(str(source))
    forged = {"../beside.txt": beside_digest, str(source): source_digest,
              "meshes/../../beside.txt": beside_digest, "meshes/old.stl": source_digest}
    (out / "meshes" / "old.stl").symlink_to(source)  # a symlink in --out, to a source
    manifest["files"].update(forged)
    (out / MANIFEST_NAME).write_text(json.dumps(manifest))
    assert _collision(urdf, out) == 0
    assert beside.read_text() == "keep me" and source.exists()
    assert (out / "meshes" / "old.stl").is_symlink()
    assert "ignoring the manifest entry '../beside.txt'" in capsys.readouterr().err
    written = json.loads((out / MANIFEST_NAME).read_text())["files"]
    assert not set(forged) & set(written)


def test_a_subfolder_of_out_leading_elsewhere_is_refused(package, capsys):
    urdf = _urdf(package, {"a": "package://demo/meshes/a.stl"})
    out = package.parent / "out"
    out.mkdir()
    elsewhere = package.parent / "elsewhere"
    elsewhere.mkdir()
    (out / "meshes").symlink_to(elsewhere)
    assert _collision(urdf, out) == 2
    assert "outside the output folder" in capsys.readouterr().err
    assert list(elsewhere.iterdir()) == [] and sorted(os.listdir(out)) == ["meshes"]


@pytest.mark.parametrize("how", ["symlink", "dotdot", "file-uri", "absolute"])
def test_a_mesh_out_of_its_package_is_a_finding_not_a_read(package, tmp_path, capsys, how):
    secret = tmp_path / "secret.stl"
    write_binary_stl(secret, box_triangles((0.5, 0.5, 0.5)))
    if how == "symlink":
        (package / "meshes" / "link.stl").symlink_to(secret)
        mesh = "package://demo/meshes/link.stl"
    elif how == "dotdot":
        mesh = "../../secret.stl"
    elif how == "file-uri":
        mesh = secret.as_uri()
    else:
        mesh = str(secret)
    urdf = _urdf(package, {"a": "package://demo/meshes/a.stl", "s": mesh})
    out = tmp_path / "out"
    assert _collision(urdf, out, "--format", "json") == 1
    report = json.loads(capsys.readouterr().out)
    links = {link["link"]: link for link in report["links"]}
    assert links["s"]["status"] == "failed"
    assert links["s"]["findings"][0]["code"] == "mesh-unresolved"
    assert sorted(os.listdir(out / "meshes")) == ["a.stl"]  # no copy of the secret


def test_an_absolute_mesh_is_read_when_the_config_allows_it(package, tmp_path, capsys):
    outside = tmp_path / "shared.stl"
    write_binary_stl(outside, box_triangles((0.5, 0.5, 0.5)))
    (package / "robotdesc.toml").write_text("[meshes]\nallow_absolute_paths = true\n")
    urdf = _urdf(package, {"s": str(outside)})
    assert _collision(urdf, tmp_path / "out") == 0
    assert sorted(os.listdir(tmp_path / "out" / "meshes")) == ["s.stl"]


def test_an_output_onto_a_source_mesh_is_refused(package, capsys):
    """--into-source-dir with the meshes folder itself: a planned file that is a source mesh
    of the run is never replaced."""
    urdf = _urdf(package, {"a": "package://demo/meshes/a.stl"})
    before = (package / "meshes" / "a.stl").read_bytes()
    assert main(["collision", str(urdf), "--method", "hull", "-j", "1",
                 "--out", str(package), "--into-source-dir"]) == 2
    assert "refusing to" in capsys.readouterr().err
    assert (package / "meshes" / "a.stl").read_bytes() == before


def test_collision_cache_entries_swapped_or_replaced_are_recomputed(package, tmp_path):
    import robotdesc

    urdf = _urdf(package, {"a": "package://demo/meshes/a.stl",
                           "b": "package://demo/meshes/b.stl"})
    robot = robotdesc.load(str(urdf))
    cache = tmp_path / "cache"

    def hulls(**options) -> list:
        result = robotdesc.generate_collision(robot, "hull", jobs=1, **options)
        return [(o.report.link, [p.vertices.max(axis=0).round(6).tolist() for p in o.parts])
                for o in result.outcomes]

    clean = hulls(use_cache=False)
    assert hulls(cache_dir=str(cache)) == clean
    entries = sorted((cache / "collision-v1").rglob("*.npz"))
    assert len(entries) == 2
    first, second = (p.read_bytes() for p in entries)
    entries[0].write_bytes(second)
    entries[1].write_bytes(first)
    assert hulls(cache_dir=str(cache)) == clean
    for entry in sorted((cache / "collision-v1").rglob("*.npz")):
        entry.unlink()
        os.mkfifo(entry)
    assert hulls(cache_dir=str(cache)) == clean  # returns: a FIFO is never opened for reading
