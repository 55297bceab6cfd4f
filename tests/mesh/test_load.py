"""Loading mesh files: formats, the URDF scale, COLLADA units, and malformed input."""

from __future__ import annotations

import os

import numpy as np
import pytest

from robotdesc.mesh.load import load_mesh
from robotdesc.mesh.mass import volume_integrals
from robotdesc.mesh.validate import MeshError, MeshErrorKind

from .builders import box_triangles, write_binary_stl, write_collada, write_obj


def _volume(mesh) -> float:
    return volume_integrals(mesh.triangles).volume


def test_stl_in_millimetres_with_urdf_scale(tmp_path):
    path = write_binary_stl(tmp_path / "mm.stl", box_triangles((100.0, 200.0, 300.0)))
    raw = load_mesh(path)
    assert raw.triangles.dtype == np.float64
    assert _volume(raw) == pytest.approx(6e6)
    scaled = load_mesh(path, scale=(0.001, 0.001, 0.001))
    assert _volume(scaled) == pytest.approx(6e-3)
    assert scaled.scale == (0.001, 0.001, 0.001) and not scaled.mirrored


def test_mirroring_scale_keeps_normals_outward(tmp_path, box_soup):
    path = write_binary_stl(tmp_path / "box.stl", box_soup)
    mirrored = load_mesh(path, scale=(-1.0, 1.0, 1.0))
    assert mirrored.mirrored
    assert _volume(mirrored) == pytest.approx(6.0)


@pytest.mark.parametrize("scale", [(0.0, 1.0, 1.0), (float("nan"), 1.0, 1.0)])
def test_bad_scale(tmp_path, box_soup, scale):
    path = write_binary_stl(tmp_path / "box.stl", box_soup)
    with pytest.raises(MeshError) as caught:
        load_mesh(path, scale=scale)
    assert caught.value.kind is MeshErrorKind.BAD_SCALE


def test_collada_unit_millimetre_is_honoured(tmp_path):
    path = write_collada(tmp_path / "mm.dae", box_triangles((100.0, 200.0, 300.0)),
                         unit_meter=0.001)
    mesh = load_mesh(path)
    assert mesh.unit_meter == 0.001
    assert _volume(mesh) == pytest.approx(6e-3)
    both = load_mesh(path, scale=(2.0, 2.0, 2.0))
    assert _volume(both) == pytest.approx(6e-3 * 8)


def test_collada_without_unit_is_metres(tmp_path, box_soup):
    mesh = load_mesh(write_collada(tmp_path / "m.dae", box_soup))
    assert mesh.unit_meter == 1.0
    assert _volume(mesh) == pytest.approx(6.0)


def test_collada_node_transform_is_applied(tmp_path, box_soup):
    matrix = np.identity(4)
    matrix[:3, 3] = (1.0, 2.0, 3.0)
    mesh = load_mesh(write_collada(tmp_path / "moved.dae", box_soup, matrix=matrix))
    centre = volume_integrals(mesh.triangles).properties().center_of_mass
    assert centre == pytest.approx((1.0, 2.0, 3.0))


def test_collada_mirroring_node_keeps_normals_outward(tmp_path, box_soup):
    matrix = np.diag([1.0, -1.0, 1.0, 1.0])
    mesh = load_mesh(write_collada(tmp_path / "mirror.dae", box_soup, matrix=matrix))
    assert _volume(mesh) == pytest.approx(6.0)


def test_collada_scene_without_geometry(tmp_path, box_soup):
    path = write_collada(tmp_path / "empty.dae", box_soup, instantiate=False)
    with pytest.raises(MeshError) as caught:
        load_mesh(path)
    assert caught.value.kind is MeshErrorKind.EMPTY
    assert "places none of the 1 geometries" in str(caught.value)


def test_collada_that_is_not_xml(tmp_path):
    path = tmp_path / "broken.dae"
    path.write_text("<COLLADA><asset>")
    with pytest.raises(MeshError) as caught:
        load_mesh(path)
    assert caught.value.kind is MeshErrorKind.MALFORMED
    assert "broken.dae" in str(caught.value)


def test_collada_index_out_of_range(tmp_path, box_soup):
    path = write_collada(tmp_path / "bad.dae", box_soup)
    path.write_text(path.read_text().replace("<p>0 1 2 ", "<p>0 1 999 "))
    with pytest.raises(MeshError) as caught:
        load_mesh(path)
    assert caught.value.kind in (MeshErrorKind.BAD_INDEX, MeshErrorKind.MALFORMED)


def test_obj(tmp_path, box_soup):
    from robotdesc.mesh.health import merge_vertices

    vertices, faces = merge_vertices(box_soup)
    mesh = load_mesh(write_obj(tmp_path / "box.obj", vertices, faces))
    assert mesh.format == "obj"
    assert _volume(mesh) == pytest.approx(6.0)


def test_obj_with_nan_vertex(tmp_path, box_soup):
    from robotdesc.mesh.health import merge_vertices

    vertices, faces = merge_vertices(box_soup)
    vertices[0, 0] = np.nan
    with pytest.raises(MeshError) as caught:
        load_mesh(write_obj(tmp_path / "nan.obj", vertices, faces))
    assert caught.value.kind is MeshErrorKind.NON_FINITE


def test_glb_round_trip(tmp_path, box_soup):
    trimesh = pytest.importorskip("trimesh")
    from robotdesc.mesh.health import merge_vertices

    vertices, faces = merge_vertices(box_soup)
    path = tmp_path / "box.glb"
    trimesh.Trimesh(vertices, faces, process=False).export(path)
    assert _volume(load_mesh(path)) == pytest.approx(6.0)


def test_unsupported_format(tmp_path):
    path = tmp_path / "part.step"
    path.write_text("ISO-10303-21;")
    with pytest.raises(MeshError) as caught:
        load_mesh(path)
    assert caught.value.kind is MeshErrorKind.UNSUPPORTED


def test_lfs_pointer_dae(tmp_path):
    path = tmp_path / "Cronstain.dae"
    path.write_text("version https://git-lfs.github.com/spec/v1\noid sha256:00\nsize 1\n")
    with pytest.raises(MeshError) as caught:
        load_mesh(path)
    assert caught.value.kind is MeshErrorKind.LFS_POINTER


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this platform")
def test_fifo_is_refused_without_blocking(tmp_path):
    path = tmp_path / "pipe.stl"
    os.mkfifo(path)
    with pytest.raises(MeshError) as caught:
        load_mesh(path)
    assert "not a regular file" in str(caught.value)


def test_multi_body_collada_from_example_robot_data(robots_dir):
    trimesh = pytest.importorskip("trimesh")
    path = robots_dir / "ur_description/meshes/ur3/visual/forearm.dae"
    mesh = load_mesh(path)
    scene = trimesh.load_scene(path)
    assert mesh.format == "dae" and mesh.bodies == 6
    assert len(mesh.triangles) == sum(len(g.faces) for g in scene.dump())
    low, high = scene.bounds
    np.testing.assert_allclose(mesh.triangles.reshape(-1, 3).min(axis=0), low, atol=1e-9)
    np.testing.assert_allclose(mesh.triangles.reshape(-1, 3).max(axis=0), high, atol=1e-9)


def test_collada_with_a_broken_material_keeps_its_geometry(tmp_path, box_soup):
    """pycollada drops a node bound to a material it cannot find; assimp (RViz) draws the
    geometry: robotdesc reads it and records the broken reference instead."""
    path = write_collada(tmp_path / "m.dae", box_soup, material="#nowhere-material")
    mesh = load_mesh(path)
    assert len(mesh.triangles) == len(box_soup)
    assert any("nowhere-material" in text for text in mesh.broken_references)


def test_collada_with_a_missing_texture_image(tmp_path, box_soup):
    path = write_collada(tmp_path / "t.dae", box_soup, image="skin.png")
    assert load_mesh(path).broken_references == ("texture image 'skin.png' does not exist",)
    (tmp_path / "skin.png").write_bytes(b"")
    assert load_mesh(path).broken_references == ()


def test_sound_collada_has_no_broken_references(tmp_path, box_soup):
    assert load_mesh(write_collada(tmp_path / "ok.dae", box_soup)).broken_references == ()


def test_anymal_foot_reads_as_assimp_does(robots_dir):
    """example-robot-data's anymal_foot.dae binds a material whose effect samples an
    undefined surface: assimp loads its 4,604 faces, and so does robotdesc."""
    path = robots_dir / "anymal_b_simple_description/meshes/foot/anymal_foot.dae"
    mesh = load_mesh(path)
    assert len(mesh.triangles) == 4604
    assert any("carbon_fibre_001" in text for text in mesh.broken_references)


def test_collada_with_a_text_node_over_libxml2s_limit_is_read(tmp_path, box_soup):
    """go1's and b1's trunk.dae hold float arrays over 10 MB: large, not malformed."""
    path = write_collada(tmp_path / "big.dae", box_soup)
    head = f'count="{box_soup.size}">'
    text = path.read_text()
    assert head in text
    path.write_text(text.replace(head, head + " " * 10_000_001, 1))
    assert len(load_mesh(path).triangles) == len(box_soup)
