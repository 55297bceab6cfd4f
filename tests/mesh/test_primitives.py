"""Analytic primitives against finely tessellated meshes of the same shapes."""

from __future__ import annotations

import numpy as np
import pytest

from robotdesc.mesh.mass import volume_integrals
from robotdesc.mesh.primitives import primitive_properties
from robotdesc.model.elements import Box, Capsule, Cylinder, Sphere

trimesh = pytest.importorskip("trimesh")


@pytest.mark.parametrize("geometry, mesh", [
    (Box((0.1, 0.2, 0.3)), lambda: trimesh.creation.box((0.1, 0.2, 0.3))),
    (Sphere(0.2), lambda: trimesh.creation.icosphere(subdivisions=6, radius=0.2)),
    (Cylinder(0.1, 0.5), lambda: trimesh.creation.cylinder(radius=0.1, height=0.5, sections=512)),
    (Capsule(0.1, 0.4), lambda: trimesh.creation.capsule(height=0.4, radius=0.1,
                                                           count=[256, 256])),
])
def test_matches_a_fine_mesh(geometry, mesh):
    analytic = primitive_properties(geometry)
    measured = volume_integrals(mesh().triangles).properties()
    assert analytic.volume == pytest.approx(measured.volume, rel=2e-3)
    assert analytic.center_of_mass == pytest.approx((0, 0, 0), abs=1e-12)
    np.testing.assert_allclose(analytic.inertia_matrix(), measured.inertia_matrix(), rtol=3e-3,
                               atol=1e-6 * np.abs(analytic.inertia_matrix()).max())


def test_box_is_exact():
    props = primitive_properties(Box((1.0, 2.0, 3.0)))
    assert props.mass == 6.0
    assert props.principal_moments() == pytest.approx((2.5, 5.0, 6.5))


@pytest.mark.parametrize("geometry", [Box((1.0, -1.0, 1.0)), Sphere(float("nan")),
                                      Cylinder(0.1, float("inf"))])
def test_bad_dimensions(geometry):
    with pytest.raises(ValueError):
        primitive_properties(geometry)
