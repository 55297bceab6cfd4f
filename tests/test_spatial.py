"""Pure-Python tensor arithmetic and rotations against numpy."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from robotdesc.spatial import (
    ZERO,
    compose,
    conjugated,
    cross,
    frobenius,
    minimum_trace,
    parallel_axis,
    perpendicular_axes,
    principal_axes,
    principal_moments,
    rotate,
    rotated,
    rotation_quaternion,
    rotation_rpy,
    rpy_matrix,
    rpy_quaternion,
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


def _quaternion_matrix(q) -> np.ndarray:
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


@pytest.mark.parametrize("seed", range(20))
def test_rpy_round_trips_and_quaternions_agree(seed: int) -> None:
    rng = np.random.default_rng(seed)
    rpy = (rng.uniform(-math.pi, math.pi), rng.uniform(-1.5, 1.5), rng.uniform(-math.pi, math.pi))
    matrix = rpy_rotation(rpy)
    assert rotation_rpy(matrix) == pytest.approx(rpy, abs=1e-12)
    assert rotation_rpy(rpy_matrix(rpy)) == pytest.approx(rpy, abs=1e-12)  # arrays too
    for q in (rpy_quaternion(rpy), rotation_quaternion(matrix)):
        assert math.isclose(sum(v * v for v in q), 1.0)
        assert np.allclose(_quaternion_matrix(q), matrix, atol=1e-12)


def test_rotation_rpy_in_gimbal_lock_puts_the_turn_in_yaw() -> None:
    roll, pitch, yaw = rotation_rpy(rpy_rotation((0.4, math.pi / 2, 0.1)))
    assert roll == 0.0 and pitch == pytest.approx(math.pi / 2)
    assert np.allclose(rpy_rotation((roll, pitch, yaw)), rpy_rotation((0.4, math.pi / 2, 0.1)))


@pytest.mark.parametrize("rpy", [(math.pi, 0, 0), (0, math.pi, 0), (0, 0, math.pi),
                                 (math.pi / 2, 0, math.pi), (0, 0, 0)])
def test_rotation_quaternion_of_half_turns(rpy) -> None:
    """Each branch of the largest-component choice."""
    matrix = rpy_rotation(rpy)
    assert np.allclose(_quaternion_matrix(rotation_quaternion(matrix)), matrix, atol=1e-12)


@pytest.mark.parametrize("axis", [(1.0, 0.0, 0.0), (0.0, 0.0, 1.0), (0.6, 0.0, 0.8),
                                  (0.0, -1.0, 0.0)])
def test_perpendicular_axes_complete_a_right_handed_frame(axis) -> None:
    u, v = perpendicular_axes(axis)
    frame = np.array([u, v, axis])
    assert np.allclose(frame @ frame.T, np.identity(3), atol=1e-12)
    assert np.allclose(cross(u, v), axis, atol=1e-12)


def test_principal_axes_diagonalize_with_a_proper_rotation() -> None:
    tensor = np.array(rotated(((1.0, 0, 0), (0, 2.0, 0), (0, 0, 3.0)), (0.3, -0.2, 0.9)))
    moments, axes = principal_axes(tensor)
    assert moments == pytest.approx([1.0, 2.0, 3.0])
    assert np.linalg.det(axes) == pytest.approx(1.0)
    assert np.allclose(axes.T @ tensor @ axes, np.diag(moments), atol=1e-12)
    nan_moments, identity = principal_axes(np.full((3, 3), np.nan))
    assert np.isnan(nan_moments).all() and (identity == np.identity(3)).all()


def test_one_implementation_of_rotations_in_the_package() -> None:
    """rpy -> matrix, matrix -> rpy, quaternions and poses are spatial's, nobody else's."""
    src = Path(__file__).resolve().parent.parent / "src" / "robotdesc"
    pattern = re.compile(r"^\s*def (pose_matrix|rpy\w*|\w*_rpy|\w*quat\w*|principal_axes)\(",
                         re.MULTILINE)
    found = {(path.relative_to(src).as_posix(), name)
             for path in src.rglob("*.py")
             for name in pattern.findall(path.read_text(encoding="utf-8"))}
    assert {path for path, _ in found} == {"spatial.py"}, found
