"""The equivalent inertia box (Gazebo's inertia view)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from robotdesc.model.elements import Inertia, Inertial, Pose
from robotdesc.view.inertia_box import box_edges, inertia_box


def box_inertial(mass, size, xyz=(0.0, 0.0, 0.0), rpy=(0.0, 0.0, 0.0)) -> Inertial:
    a, b, c = size
    moments = (mass * (b * b + c * c) / 12, mass * (a * a + c * c) / 12,
               mass * (a * a + b * b) / 12)
    return Inertial(Pose(xyz, rpy), mass, Inertia(moments[0], 0, 0, moments[1], 0, moments[2]))


def test_a_box_inertial_gives_back_its_box() -> None:
    box = inertia_box("l", box_inertial(3.0, (0.1, 0.4, 0.2), xyz=(1, 2, 3)))
    assert box is not None and box.valid
    assert sorted(box.size) == pytest.approx([0.1, 0.2, 0.4])
    assert np.allclose(box.transform[:3, 3], [1, 2, 3])
    # the longest edge lies along link y (the axis of the smallest moment... of the box)
    longest = int(np.argmax(box.size))
    assert np.allclose(np.abs(box.transform[:3, longest]), [0, 1, 0])
    assert np.isclose(np.linalg.det(box.transform[:3, :3]), 1.0)


def test_the_inertial_rotation_turns_the_box() -> None:
    box = inertia_box("l", box_inertial(1.0, (0.1, 0.4, 0.2), rpy=(0, 0, math.pi / 2)))
    longest = int(np.argmax(box.size))
    assert np.allclose(np.abs(box.transform[:3, longest]), [1, 0, 0])  # y turned onto x


def test_the_placed_box_moves_with_the_link() -> None:
    pose = np.identity(4)
    pose[:3, 3] = (0, 0, 1)
    placed = inertia_box("l", box_inertial(1.0, (1, 1, 1))).placed(pose)
    assert np.allclose(placed.transform[:3, 3], [0, 0, 1])


def test_moments_that_no_body_has_are_flagged_and_clamped() -> None:
    (a, b, c), valid = box_edges(1.0, (1.0, 1.0, 3.0))  # 3 > 1 + 1
    assert not valid and c == 0.0 and a > 0 and b > 0


@pytest.mark.parametrize("inertial", [
    None,
    Inertial(Pose(), None, Inertia(1, 0, 0, 1, 0, 1)),
    Inertial(Pose(), 0.0, Inertia(1, 0, 0, 1, 0, 1)),
    Inertial(Pose(), 1.0, None),
    Inertial(Pose(), 1.0, Inertia(float("nan"), 0, 0, 1, 0, 1)),
])
def test_no_box_without_a_positive_mass_and_a_finite_tensor(inertial) -> None:
    assert inertia_box("l", inertial) is None
