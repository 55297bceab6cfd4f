"""Mass properties from the volume integral, against analytic values and MeshLab's."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from robotdesc.mesh.load import load_mesh
from robotdesc.mesh.mass import (
    MassProperties,
    bounds,
    combine,
    link_mass_properties,
    volume_integrals,
)
from robotdesc.spatial import rpy_matrix

from .builders import box_triangles

REFERENCE = json.loads((Path(__file__).parent / "data/meshlab_reference.json").read_text())


def test_box_is_exact():
    props = volume_integrals(box_triangles((1.0, 2.0, 3.0), center=(5.0, 6.0, 7.0))).properties()
    assert props.volume == pytest.approx(6.0, rel=1e-12)
    assert props.center_of_mass == pytest.approx((5.0, 6.0, 7.0), rel=1e-12)
    expected = np.diag([6.0 * (4 + 9) / 12, 6.0 * (1 + 9) / 12, 6.0 * (1 + 4) / 12])
    np.testing.assert_allclose(props.inertia_matrix(), expected, rtol=1e-12, atol=1e-12)


def test_far_from_origin_keeps_precision():
    near = volume_integrals(box_triangles((0.01, 0.02, 0.03))).properties()
    far = volume_integrals(box_triangles((0.01, 0.02, 0.03), center=(1e3, -2e3, 5e2))).properties()
    np.testing.assert_allclose(far.inertia_matrix(), near.inertia_matrix(), rtol=1e-6,
                               atol=1e-6 * np.abs(near.inertia_matrix()).max())


def test_sphere_converges_to_analytic():
    trimesh = pytest.importorskip("trimesh")
    sphere = trimesh.creation.icosphere(subdivisions=6, radius=0.5)
    props = volume_integrals(sphere.triangles).properties()
    volume = 4 / 3 * math.pi * 0.5 ** 3
    assert props.volume == pytest.approx(volume, rel=1e-3)
    np.testing.assert_allclose(props.inertia_matrix(), np.eye(3) * 0.4 * volume * 0.25,
                               rtol=2e-3, atol=1e-9)


def test_products_of_inertia_use_the_urdf_sign():
    # a box rotated 45 degrees about z: Ixy = -integral(x*y dm) is negative here
    rotation = rpy_matrix((0.0, 0.0, math.pi / 4))
    soup = box_triangles((2.0, 1.0, 1.0)) @ rotation.T
    props = volume_integrals(soup).properties()
    expected = rotation @ np.diag([2 * 2 / 12, 2 * 5 / 12, 2 * 5 / 12]) @ rotation.T
    np.testing.assert_allclose(props.inertia_matrix(), expected, atol=1e-12)
    assert props.inertia[0][1] < 0


def test_chunking_does_not_change_the_result():
    trimesh = pytest.importorskip("trimesh")
    soup = trimesh.creation.icosphere(subdivisions=4).triangles
    whole = volume_integrals(soup, chunk=len(soup)).values
    pieces = volume_integrals(soup, chunk=97).values
    np.testing.assert_allclose(pieces, whole, rtol=1e-12, atol=1e-15)


def test_inverted_integral_is_negative_and_properties_refuse_it():
    inverted = volume_integrals(box_triangles()[:, ::-1])
    assert inverted.volume == pytest.approx(-6.0)
    with pytest.raises(ValueError):
        inverted.properties()
    assert inverted.flipped().properties().volume == pytest.approx(6.0)


def test_bounds():
    low, high = bounds(box_triangles((1.0, 2.0, 3.0), center=(1.0, 0.0, 0.0)), chunk=5)
    assert low == (0.5, -1.0, -1.5) and high == (1.5, 1.0, 1.5)


def test_rpy_matches_fixed_axis_rotations():
    roll, pitch, yaw = 0.3, -0.7, 1.1

    def axis(k, angle):
        c, s = math.cos(angle), math.sin(angle)
        m = np.eye(3)
        i, j = [(1, 2), (2, 0), (0, 1)][k]
        m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
        return m

    expected = axis(2, yaw) @ axis(1, pitch) @ axis(0, roll)
    np.testing.assert_allclose(rpy_matrix((roll, pitch, yaw)), expected, atol=1e-15)


def test_combine_equals_integral_of_the_union():
    a = box_triangles((1.0, 1.0, 1.0), center=(0.0, 0.0, 0.0))
    b = box_triangles((2.0, 1.0, 1.0), center=(3.0, 1.0, -1.0))
    union = volume_integrals(np.concatenate([a, b])).properties()
    summed = combine([volume_integrals(a).properties(), volume_integrals(b).properties()])
    assert summed.mass == pytest.approx(union.mass)
    assert summed.center_of_mass == pytest.approx(union.center_of_mass)
    np.testing.assert_allclose(summed.inertia_matrix(), union.inertia_matrix(), rtol=1e-12)


def test_link_frame_origins_and_declared_mass():
    box = volume_integrals(box_triangles((1.0, 2.0, 3.0))).properties()
    xyz, rpy = (0.5, 0.0, 0.0), (0.0, 0.0, math.pi / 2)
    link = link_mass_properties([(box, xyz, rpy)], mass=3.0)
    assert link.mass == pytest.approx(3.0) and link.volume == pytest.approx(6.0)
    assert link.center_of_mass == pytest.approx(xyz)
    # rotated 90 degrees about z: the x and y moments swap; density 0.5 halves them
    np.testing.assert_allclose(np.diag(link.inertia_matrix()),
                               [0.5 * 5.0, 0.5 * 6.5, 0.5 * 2.5], rtol=1e-12)
    assert link.density == pytest.approx(0.5)


def test_zero_mass_combination_is_not_nan():
    empty = combine([])
    assert empty.mass == 0.0 and not np.isnan(empty.inertia_matrix()).any()
    assert MassProperties(0.0, (0, 0, 0), empty.inertia, 0.0).scaled_to_mass(1.0).mass == 1.0


@pytest.mark.parametrize("name", sorted(REFERENCE["meshes"]))
def test_agrees_with_meshlab(robots_dir, name):
    reference = REFERENCE["meshes"][name]
    mesh = load_mesh(robots_dir / name)
    props = volume_integrals(mesh.triangles).properties()
    inertia = np.array(reference["inertia"])
    size = np.linalg.norm(np.subtract(*bounds(mesh.triangles)))
    assert props.volume == pytest.approx(reference["volume"], rel=1e-6)
    # relative to the mesh's size and largest moment: entries that are zero by symmetry
    # come out as 1e-20 in one program and 1e-22 in the other
    assert np.abs(np.subtract(props.center_of_mass, reference["center_of_mass"])).max() \
        <= 1e-6 * size
    assert np.abs(props.inertia_matrix() - inertia).max() <= 1e-6 * np.abs(inertia).max()
