"""Display reduction: welding and vertex clustering."""

from __future__ import annotations

import numpy as np
from mesh.builders import box_triangles

from robotdesc.view.shapes import sphere_mesh
from robotdesc.view.simplify import cluster, drop_degenerate, reduce_faces, weld


def test_weld_merges_the_corners_of_a_soup() -> None:
    vertices, faces = weld(box_triangles())
    assert len(vertices) == 8 and len(faces) == 12
    assert np.allclose(vertices[faces], box_triangles())


def test_drop_degenerate() -> None:
    faces = np.array([[0, 1, 2], [0, 0, 1], [3, 4, 3]])
    assert drop_degenerate(faces).tolist() == [[0, 1, 2]]


def test_reduction_meets_the_budget_and_keeps_the_extent() -> None:
    vertices, faces = sphere_mesh(1.0, segments=200)
    assert len(faces) > 15_000
    small_v, small_f = reduce_faces(vertices, faces, 2_000)
    assert 0 < len(small_f) <= 2_000
    assert np.allclose(small_v.min(axis=0), -1.0, atol=0.05)
    assert np.allclose(small_v.max(axis=0), 1.0, atol=0.05)
    assert small_f.max() < len(small_v)


def test_reduction_leaves_small_meshes_alone() -> None:
    vertices, faces = sphere_mesh(1.0)
    same_v, same_f = reduce_faces(vertices, faces, 10_000)
    assert same_v is vertices and same_f is faces


def test_cluster_returns_valid_indices() -> None:
    vertices, faces = sphere_mesh(1.0, segments=64)
    merged, reduced = cluster(vertices, faces, 100)
    assert len(reduced) <= 100 and reduced.min() >= 0 and reduced.max() < len(merged)
