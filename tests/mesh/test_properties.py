"""Pure-Python rigid-body properties: transforms, sums and bounds, checked against numpy."""

from __future__ import annotations

import numpy as np
import pytest

from robotdesc.mesh.mass import volume_integrals
from robotdesc.mesh.primitives import box_properties
from robotdesc.mesh.properties import MassProperties, combine, moved_bounds
from robotdesc.spatial import rpy_rotation

from .builders import box_triangles

XYZ, RPY = (0.1, -0.2, 0.3), (0.4, -0.5, 0.6)


def test_transformed_matches_the_numpy_formula() -> None:
    body = volume_integrals(box_triangles((0.1, 0.2, 0.4), center=(0.05, 0.0, 0.1))).properties()
    moved = body.transformed(XYZ, RPY)
    r = np.array(rpy_rotation(RPY))
    np.testing.assert_allclose(moved.center_of_mass, r @ body.center_of_mass + XYZ, atol=1e-15)
    np.testing.assert_allclose(moved.inertia, r @ np.array(body.inertia) @ r.T, atol=1e-15)
    assert body.transformed() is body  # frames that coincide: nothing to do


def test_combine_equals_the_integral_of_the_union() -> None:
    a, b = box_triangles((1, 1, 1), (0, 0, 0)), box_triangles((1, 1, 1), (1.0, 0.5, 0.0))
    summed = combine([volume_integrals(a).properties(), volume_integrals(b).properties()])
    union = volume_integrals(np.concatenate([a, b])).properties()
    assert summed.mass == pytest.approx(union.mass)
    np.testing.assert_allclose(summed.center_of_mass, union.center_of_mass, atol=1e-14)
    np.testing.assert_allclose(summed.inertia, union.inertia, rtol=1e-12, atol=1e-14)


def test_scaling_and_principal_moments() -> None:
    box = box_properties(0.1, 0.2, 0.4).transformed(rpy=RPY).scaled_to_mass(2.0)
    assert box.mass == 2.0 and box.density == pytest.approx(2.0 / 0.008)
    np.testing.assert_allclose(box.principal_moments(), np.linalg.eigvalsh(box.inertia_matrix()),
                               rtol=1e-12)
    empty = MassProperties(0.0, (0.0, 0.0, 0.0), combine([]).inertia, 0.0)
    assert empty.scaled_to_mass(1.0).inertia == combine([]).inertia  # no NaN from 0 / 0


def test_moved_bounds_hold_every_moved_corner() -> None:
    box = ((-0.1, -0.2, -0.3), (0.1, 0.2, 0.3))
    low, high = moved_bounds(box, XYZ, RPY)
    corners = np.array([[x, y, z] for x in (-0.1, 0.1) for y in (-0.2, 0.2) for z in (-0.3, 0.3)])
    moved = corners @ np.array(rpy_rotation(RPY)).T + XYZ
    np.testing.assert_allclose(low, moved.min(axis=0), atol=1e-15)
    np.testing.assert_allclose(high, moved.max(axis=0), atol=1e-15)
