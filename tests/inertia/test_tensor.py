"""Pure-Python tensor arithmetic against numpy."""

from __future__ import annotations

import numpy as np
import pytest

from robotdesc.inertia.tensor import minimum_trace, principal_moments, rotated, triangle_violation


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
