"""Pure-Python tensor arithmetic against numpy."""

from __future__ import annotations

import numpy as np
import pytest

from robotdesc.spatial import (
    ZERO,
    compose,
    conjugated,
    frobenius,
    minimum_trace,
    parallel_axis,
    principal_moments,
    rotate,
    rotated,
    rpy_rotation,
    scaled,
    summed,
    triangle_violation,
)


@pytest.mark.parametrize("seed", range(20))
def test_principal_moments_match_numpy(seed: int) -> None:
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(3, 3))
    matrix = a @ a.T
    assert principal_moments(matrix.tolist()) == pytest.approx(np.linalg.eigvalsh(matrix),
                                                                rel=1e-9, abs=1e-12)


def test_rotation_keeps_principal_moments() -> None:
    matrix = ((1.0, 0.0, 0.0), (0.0, 2.0, 0.0), (0.0, 0.0, 2.5))
    assert principal_moments(rotated(matrix, (0.3, -0.2, 1.1))) == pytest.approx((1, 2, 2.5))


def test_triangle_violation_and_minimum_trace() -> None:
    assert triangle_violation((1.0, 1.0, 3.0)) == pytest.approx(1.0)
    assert triangle_violation((1.0, 1.0, 2.0)) == 0.0
    # a 1 kg osmium ball: radius 21.9 mm, trace 6/5 m R^2
    assert minimum_trace(1.0) == pytest.approx(1.2 * 0.021942 ** 2, rel=1e-3)


def _rotation(seed: int) -> np.ndarray:
    q, _ = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    return q


@pytest.mark.parametrize("seed", range(5))
def test_conjugated_compose_and_rotate_match_numpy(seed: int) -> None:
    r, s = _rotation(seed), _rotation(seed + 100)
    a = np.random.default_rng(seed).normal(size=(3, 3))
    m = a @ a.T
    np.testing.assert_allclose(conjugated(m.tolist(), r.tolist()), r @ m @ r.T, atol=1e-14)
    np.testing.assert_allclose(compose(r.tolist(), s.tolist()), r @ s, atol=1e-14)
    np.testing.assert_allclose(rotate(r.tolist(), (1.0, -2.0, 0.5)), r @ [1.0, -2.0, 0.5],
                               atol=1e-14)


def test_rpy_rotation_is_urdf_fixed_axis_order() -> None:
    roll, pitch, yaw = 0.3, -0.7, 1.9
    rx = np.array([[1, 0, 0], [0, np.cos(roll), -np.sin(roll)], [0, np.sin(roll), np.cos(roll)]])
    ry = np.array([[np.cos(pitch), 0, np.sin(pitch)], [0, 1, 0],
                   [-np.sin(pitch), 0, np.cos(pitch)]])
    rz = np.array([[np.cos(yaw), -np.sin(yaw), 0], [np.sin(yaw), np.cos(yaw), 0], [0, 0, 1]])
    np.testing.assert_allclose(rpy_rotation((roll, pitch, yaw)), rz @ ry @ rx, atol=1e-15)


def test_parallel_axis_and_norms() -> None:
    # a point mass of 2 kg at (1, 2, 0): I = m (|d|^2 E - d d^T)
    moved = parallel_axis(ZERO, 2.0, (1.0, 2.0, 0.0))
    assert moved == ((8.0, -4.0, 0.0), (-4.0, 2.0, 0.0), (0.0, 0.0, 10.0))
    assert frobenius(moved) == pytest.approx(float(np.linalg.norm(np.array(moved))))
    assert summed([moved, moved]) == scaled(moved, 2.0)


def test_principal_moments_of_a_thin_rotated_rod() -> None:
    # a rod: one moment a millionth of the others, in a rotated frame
    rod = ((1e-6, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    small, middle, large = principal_moments(rotated(rod, (0.4, 0.9, -1.3)))
    assert small == pytest.approx(1e-6, rel=1e-6)
    assert (middle, large) == pytest.approx((1.0, 1.0), rel=1e-12)
