"""Edge counts: closed, open, misoriented, non-manifold and degenerate surfaces."""

from __future__ import annotations

import numpy as np

from robotdesc.mesh.health import (
    hole_caps,
    merge_tolerance,
    merge_vertices,
    mesh_health,
    topology,
)
from robotdesc.mesh.mass import volume_integrals

from .builders import box_triangles


def test_closed_box():
    health = mesh_health(box_triangles())
    assert health.watertight and health.consistent_winding and health.encloses_volume
    assert (health.triangles, health.vertices, health.degenerate_faces) == (12, 8, 0)


def test_open_box():
    health = mesh_health(box_triangles()[2:])  # one side removed
    assert not health.watertight and not health.encloses_volume
    assert health.boundary_edges == 4 and health.hole_loops == 1
    assert health.consistent_winding


def test_one_flipped_face():
    soup = box_triangles()
    soup[5] = soup[5][::-1]
    health = mesh_health(soup)
    assert health.watertight and not health.consistent_winding
    assert health.misoriented_edges == 3 and not health.encloses_volume


def test_two_boxes_touching_along_an_edge_still_enclose_volume():
    soup = np.concatenate([box_triangles((1, 1, 1)), box_triangles((1, 1, 1), center=(1, 1, 0))])
    health = mesh_health(soup)
    assert health.nonmanifold_edges == 1 and not health.watertight
    assert health.misoriented_edges == 0 and health.encloses_volume


def test_degenerate_faces():
    soup = np.concatenate([box_triangles(), [[[0, 0, 0], [0, 0, 0], [1, 1, 1]],
                                             [[0, 0, 0], [1, 1, 1], [2, 2, 2]]]])
    assert mesh_health(soup).degenerate_faces == 2


def test_merge_treats_negative_zero_as_zero():
    soup = box_triangles(center=(0.5, 1.0, 1.5))  # corners on the coordinate planes
    soup[soup == 0.0] = -0.0
    soup[0, 0] = np.abs(soup[0, 0])
    vertices, faces = merge_vertices(soup)
    assert len(vertices) == 8
    np.testing.assert_array_equal(vertices[faces], soup)


def test_hole_caps_close_a_planar_hole_exactly():
    soup = box_triangles()[2:]
    caps = hole_caps(topology(soup))
    assert caps.shape == (4, 3, 3)
    closed = np.concatenate([soup, caps])
    assert mesh_health(closed).encloses_volume
    assert abs(volume_integrals(closed).volume - 6.0) < 1e-12


def test_crack_narrower_than_the_tolerance_is_closed():
    """An exporter's rounding: one face's corners a tenth of a nanometre off its
    neighbours'. Merged within a millionth of the size, the box is closed."""
    soup = box_triangles()
    soup[4] += 1e-10
    health = mesh_health(soup)
    assert health.watertight and health.encloses_volume and health.vertices == 8


def test_gap_wider_than_the_tolerance_stays_open():
    soup = box_triangles()
    soup[4] += 1e-3
    health = mesh_health(soup)
    assert not health.watertight and health.boundary_edges > 0


def test_merge_tolerance_is_relative_to_the_mesh_size():
    small, large = box_triangles((0.01, 0.01, 0.01)), box_triangles((10.0, 10.0, 10.0))
    assert merge_tolerance(small.reshape(-1, 3)) < merge_tolerance(large.reshape(-1, 3))
    assert merge_tolerance(large.reshape(-1, 3)) < 1e-4


def _pair_set(pairs: np.ndarray) -> set[tuple[int, int]]:
    assert all(i < j for i, j in pairs.tolist())
    return {(int(i), int(j)) for i, j in pairs}


def _every_close_pair(points: np.ndarray, limit: float) -> np.ndarray:
    """The reference: every pair compared (`limit`: the squared tolerance)."""
    squared = ((points[:, None, :] - points[None, :, :]) ** 2).sum(axis=2)
    rows, cols = np.nonzero(squared <= limit)
    keep = cols > rows
    return np.stack((rows[keep], cols[keep]), axis=1)


def test_close_pairs_without_a_grid_are_the_pairs_of_the_pairwise_comparison(monkeypatch):
    """Where the grid's cells cannot be numbered (a tolerance tiny against the cloud), the
    sweep along x finds the same pairs, also in blocks; rows with a non-finite coordinate
    are close to nothing; and no size imports scipy."""
    import sys

    from robotdesc.mesh import health

    rng = np.random.default_rng(7)
    spread = rng.uniform(-1.0, 1.0, (1500, 3))
    spread[::2, 0] = spread[1::2, 0]  # equal x: the sweep compares these
    spread[::5] = spread[1::5] + rng.normal(0, 1e-300, (300, 3))
    for points, tol in ((spread, 1e-300), (spread, 0.05), (rng.uniform(0, 1, (500, 3)), 0.08)):
        expected = _pair_set(_every_close_pair(points, tol * tol))
        assert _pair_set(health._close_pairs_swept(points, tol, tol * tol)) == expected
        assert _pair_set(health._close_pairs(points, tol)) == expected
    monkeypatch.setattr(health, "_SWEEP_PAIRS", 64)  # many blocks, a row larger than one
    points = np.concatenate([np.zeros((200, 3)), rng.uniform(0, 1, (300, 3))])
    points[:200, 1] = np.arange(200) * 0.01
    expected = _pair_set(_every_close_pair(points, 0.0004))
    assert _pair_set(health._close_pairs_swept(points, 0.02, 0.0004)) == expected
    broken = points.copy()
    broken[[3, 7], 0] = np.nan
    broken[11, 2] = np.inf
    found = _pair_set(health._close_pairs(broken, 0.02))
    assert found == {(i, j) for i, j in expected if {i, j}.isdisjoint({3, 7, 11})}
    if "scipy" not in sys.modules:  # nothing above imported it
        health._close_pairs(rng.uniform(0, 1, (20000, 3)), 1e-3)
        assert "scipy" not in sys.modules


def test_close_pairs_by_cells_are_the_pairs_of_the_pairwise_comparison():
    """The grid finds exactly the pairs every-pair comparison finds: random clouds with
    clusters, points on a lattice exactly one tolerance apart (the boundary case), repeated
    coordinates on a plane, and a tolerance wider than the cloud."""
    from robotdesc.mesh.health import _close_pairs_in_cells

    rng = np.random.default_rng(31)
    tolerance = 2.0 ** -10  # the lattice's neighbours are exactly this far apart
    clouds = []
    for n in (2, 3, 50, 700, 2048):
        base = rng.uniform(-0.2, 0.2, (n, 3))
        jitter = base[rng.integers(0, n, n // 2)] + rng.normal(0, tolerance, (n // 2, 3))
        clouds.append(np.concatenate([base, jitter]))
    lattice = np.stack(np.meshgrid(*[np.arange(6) * tolerance] * 3), axis=-1).reshape(-1, 3)
    clouds.append(lattice + 0.375)
    flat = rng.uniform(0, 0.01, (400, 3))
    flat[:, 2] = 0.25
    flat[::3, 0] = 0.005
    clouds.append(flat)
    for points in clouds:
        points = np.asarray(points, dtype=np.float64)
        for tol in (tolerance, 0.01) if len(points) > 300 else (tolerance, 0.05, 10.0):
            expected = _pair_set(_every_close_pair(points, tol * tol))
            found = _close_pairs_in_cells(points, tol, tol * tol)
            assert found is not None
            assert _pair_set(found) == expected
