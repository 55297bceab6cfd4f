"""`unique` and `unique_inverse` give what np.unique gives (robotdesc/mesh/unique.py)."""

from __future__ import annotations

import numpy as np
import pytest

from robotdesc.mesh.unique import unique, unique_inverse


@pytest.mark.parametrize("values", [
    np.zeros(0, dtype=np.int64), np.array([7]), np.array([3, 1, 3, 2, 1, 1]),
    np.random.default_rng(4).integers(-50, 50, 5_000), np.arange(100)[::-1],
])
def test_as_numpy_gives_them(values: np.ndarray) -> None:
    assert np.array_equal(unique(values), np.unique(values))
    distinct, inverse = unique_inverse(values)
    expected, expected_inverse = np.unique(values, return_inverse=True)
    assert np.array_equal(distinct, expected) and np.array_equal(inverse, expected_inverse)
    assert np.array_equal(distinct[inverse], values)
