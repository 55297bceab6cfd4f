"""The robot's size from its joint frames, and the millimetre test built on it."""

from __future__ import annotations

import numpy as np
import pytest

from robotdesc.mesh.scale_check import looks_like_millimetres, robot_size
from robotdesc.model.parse import parse_urdf

URDF = """<?xml version="1.0"?>
<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="ab" type="fixed"><parent link="a"/><child link="b"/>
    <origin xyz="0 0 1" rpy="0 1.5707963267948966 0"/></joint>
  <joint name="bc" type="fixed"><parent link="b"/><child link="c"/>
    <origin xyz="0 0 2"/></joint>
</robot>
"""


def test_robot_size_follows_rotated_joint_frames() -> None:
    robot = parse_urdf(URDF.encode(), "r.urdf")
    # b sits at (0, 0, 1) turned 90 degrees about y: its z axis is the parent's x axis
    points = np.array([[0, 0, 0], [0, 0, 1], [2, 0, 1]])
    expected = float(np.linalg.norm(points.max(axis=0) - points.min(axis=0)))
    assert robot_size(robot) == pytest.approx(expected)


def test_looks_like_millimetres() -> None:
    assert looks_like_millimetres(300.0, 1.0, [])
    assert not looks_like_millimetres(0.3, 1.0, [])
    assert looks_like_millimetres(300.0, 0.0, [0.2, 0.3, 0.4])  # judged by its peers
    assert not looks_like_millimetres(300.0, 0.0, [])
