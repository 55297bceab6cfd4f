"""The own point-to-surface distance: exact against brute force and an analytic sphere,
including at sub-millimetre scale where trimesh 5.2's query was seen to be wrong."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from robotdesc.collision.distance import (
    SurfaceIndex,
    brute_force_distances,
    point_triangle_distance,
)


def test_point_triangle_regions():
    a, b, c = np.array([[0.0, 0, 0]]), np.array([[1.0, 0, 0]]), np.array([[0.0, 1, 0]])
    cases = {(0.2, 0.2, 0.5): 0.5, (-1.0, -1.0, 0.0): np.sqrt(2), (2.0, 0.0, 0.0): 1.0,
             (0.5, -2.0, 0.0): 2.0, (1.0, 1.0, 0.0): np.sqrt(0.5) / 1.0 * 1.0 * 1.0}
    for point, expected in cases.items():
        got = point_triangle_distance(np.array([point]), a, b, c)[0]
        assert got == pytest.approx(expected, rel=1e-12)


def test_degenerate_triangle_is_measured_as_its_edges():
    a, b = np.array([[0.0, 0, 0]]), np.array([[1.0, 0, 0]])
    got = point_triangle_distance(np.array([[0.5, 1.0, 0.0]]), a, b, b.copy())
    assert got[0] == pytest.approx(1.0)


@pytest.mark.parametrize("scale", [1.0, 1e-3, 1e-4])
def test_matches_analytic_sphere_and_brute_force(scale):
    sphere = trimesh.creation.icosphere(subdivisions=5, radius=1.0)
    vertices = sphere.vertices * scale
    rng = np.random.default_rng(1)
    directions = rng.normal(size=(500, 3))
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    radii = rng.uniform(0.0, 2.0, size=500)
    points = directions * radii[:, None] * scale
    got = SurfaceIndex(vertices, sphere.faces).distances(points)
    # a point's distance to the inscribed polyhedron differs from |r - 1| by at most the sag
    edge = np.linalg.norm(sphere.vertices[sphere.edges[:, 0]] - sphere.vertices[sphere.edges[:, 1]],
                          axis=1).max()
    sag = edge ** 2 / 2  # 1 - cos(edge) for a unit sphere, generously
    assert np.all(np.abs(got / scale - np.abs(radii - 1.0)) <= sag + 1e-12)
    reference = brute_force_distances(points[:100], vertices, sphere.faces)
    np.testing.assert_allclose(got[:100], reference, rtol=1e-12, atol=1e-18)
    assert sphere.edges_unique_length.max() * scale < 2e-4 or scale == 1.0


def test_pruning_is_exact_on_a_real_mesh_with_slivers():
    from collision.conftest import LINK1, real_mesh
    from robotdesc.mesh.health import merge_vertices
    from robotdesc.mesh.load import load_mesh

    vertices, faces = merge_vertices(load_mesh(real_mesh(LINK1)).triangles)
    hull = trimesh.Trimesh(vertices, faces).convex_hull
    points, _ = trimesh.sample.sample_surface(hull, 200, seed=3)
    got = SurfaceIndex(vertices, faces).distances(points)
    np.testing.assert_allclose(got, brute_force_distances(points, vertices, faces), rtol=1e-12)
