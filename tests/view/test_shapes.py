"""Primitive meshes: closed, outward-wound, with the primitive's volume."""

from __future__ import annotations

import math

import numpy as np
import pytest

from robotdesc.mesh.mass import volume_integrals
from robotdesc.model.elements import Box, Capsule, Cylinder, MeshRef, Sphere
from robotdesc.view.shapes import primitive_mesh


def _volume(mesh) -> float:
    vertices, faces = mesh
    return volume_integrals(vertices[faces]).volume


def _closed(faces: np.ndarray) -> bool:
    """Every edge is shared by exactly two faces, once in each direction."""
    directed = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    forward = {tuple(e) for e in directed}
    return len(forward) == len(directed) and all((b, a) in forward for a, b in forward)


@pytest.mark.parametrize("geometry, exact, slack", [
    (Box((0.4, 0.2, 0.1)), 0.4 * 0.2 * 0.1, 1e-12),
    (Cylinder(0.1, 0.5), math.pi * 0.01 * 0.5, 0.03),
    (Sphere(0.2), 4 / 3 * math.pi * 0.008, 0.06),
    (Capsule(0.1, 0.3), math.pi * 0.01 * 0.3 + 4 / 3 * math.pi * 0.001, 0.06),
])
def test_primitive_meshes_are_closed_outward_and_of_the_right_volume(geometry, exact,
                                                                      slack) -> None:
    mesh = primitive_mesh(geometry)
    assert _closed(mesh[1])
    volume = _volume(mesh)
    assert volume > 0  # outward winding gives a positive signed volume
    assert volume == pytest.approx(exact, rel=slack)


def test_cylinders_lie_along_z() -> None:
    vertices, _ = primitive_mesh(Cylinder(0.1, 2.0))
    assert np.allclose(vertices[:, 2].min(), -1.0) and np.allclose(vertices[:, 2].max(), 1.0)
    assert np.abs(vertices[:, :2]).max() <= 0.1 + 1e-12


def test_a_mesh_reference_is_not_a_primitive() -> None:
    with pytest.raises(TypeError):
        primitive_mesh(MeshRef("a.stl"))
