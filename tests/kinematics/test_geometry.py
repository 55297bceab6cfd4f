"""Collision shapes' hull points (kinematics/geometry.py)."""

from __future__ import annotations

import numpy as np

from robotdesc.kinematics.geometry import CollisionShape


def test_mesh_vertices_are_distinct_and_computed_once() -> None:
    """A self-collision matrix asks at every sampled configuration (Care-O-bot's lint took
    17.9 s, 12 s of it sorting the same vertices again; 4.8 s with them kept)."""
    triangle = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    shape = CollisionShape("base", 0, np.eye(4), "mesh", triangles=np.stack([triangle] * 4))
    first = shape.local_points()
    assert first.shape == (3, 3) and not first.flags.writeable
    assert shape.local_points() is first
    placed = CollisionShape("base", 0, np.diag([1.0, 1.0, 1.0, 1.0]), "box", size=(2, 2, 2))
    assert placed.local_points().shape == (8, 3)
