"""Forward kinematics of the model's tree: joint motions, defaults, mimic joints, bad
configurations."""

from __future__ import annotations

import math

import numpy as np
import pytest

from robotdesc.errors import UsageError
from robotdesc.model.elements import Joint, JointLimit, Link, Mimic, Pose, Robot
from robotdesc.model.tree import (
    axis_rotation,
    configuration,
    default_value,
    joint_motion,
    link_transforms,
)


def chain() -> Robot:
    """base -(revolute z at x=1)-> upper -(prismatic x at x=1)-> lower; tip mimics slide."""
    joints = (
        Joint("turn", "revolute", "base", "upper", Pose((1.0, 0.0, 0.0)), (0.0, 0.0, 1.0),
              JointLimit(-3.0, 3.0)),
        Joint("slide", "prismatic", "upper", "lower", Pose((1.0, 0.0, 0.0)), (2.0, 0.0, 0.0),
              JointLimit(0.1, 0.5)),
        Joint("follow", "prismatic", "upper", "tip", Pose(), (0.0, 0.0, 1.0),
              JointLimit(-1.0, 1.0), mimic=Mimic("slide", 2.0, 0.25)),
        Joint("weld", "fixed", "lower", "tool", Pose((0.0, 0.0, 0.5), (0.0, 0.0, math.pi / 2))),
    )
    links = tuple(Link(n) for n in ("base", "upper", "lower", "tip", "tool"))
    return Robot("chain", links, joints)


def test_axis_rotation_is_a_proper_rotation_about_the_axis() -> None:
    rotation = axis_rotation(np.array([0.0, 0.0, 1.0]), math.pi / 2)
    assert np.allclose(rotation @ [1, 0, 0], [0, 1, 0])
    assert np.isclose(np.linalg.det(rotation), 1.0)


def test_joint_motion_normalises_the_axis_and_ignores_fixed_joints() -> None:
    slide = chain().joint("slide")
    assert np.allclose(joint_motion(slide, 0.3)[:3, 3], [0.3, 0, 0])  # axis 2 0 0 normalised
    assert np.allclose(joint_motion(chain().joint("weld"), 5.0), np.identity(4))


def test_default_is_zero_moved_into_the_limits() -> None:
    robot = chain()
    assert default_value(robot.joint("turn")) == 0.0
    assert default_value(robot.joint("slide")) == 0.1  # 0 lies below the lower limit


def test_link_poses_follow_the_chain_and_the_mimic_joint() -> None:
    poses = link_transforms(chain(), {"turn": math.pi / 2, "slide": 0.3})
    assert np.allclose(poses["base"], np.identity(4))
    assert np.allclose(poses["upper"][:3, 3], [1, 0, 0])
    # the slide moves along upper's x axis, which the turn rotated onto world y
    assert np.allclose(poses["lower"][:3, 3], [1, 1.3, 0])
    assert np.allclose(poses["tip"][:3, 3], [1, 0, 2 * 0.3 + 0.25])
    assert np.allclose(poses["tool"][:3, 3], [1, 1.3, 0.5])
    assert np.allclose(poses["tool"][:3, :3] @ [1, 0, 0], [-1, 0, 0])  # turn + weld yaw


def test_configuration_lists_every_moving_joint_with_mimics_resolved() -> None:
    q = configuration(chain(), {"slide": 0.2})
    assert q == pytest.approx({"turn": 0.0, "slide": 0.2, "follow": 0.65})


@pytest.mark.parametrize("values, message", [
    ({"nope": 1.0}, "'nope' is not a joint; moving joints: slide, turn$"),
    ({"weld": 1.0}, "'weld' is a fixed joint"),
    ({"follow": 1.0}, "'follow' mimics 'slide'; set 'slide' instead"),
    ({"turn": float("nan")}, "must be a finite number"),
])
def test_bad_configurations_are_usage_errors(values, message) -> None:
    with pytest.raises(UsageError, match=message):
        configuration(chain(), values)


def test_a_link_in_a_loop_is_drawn_at_the_origin() -> None:
    robot = Robot("loop", (Link("a"), Link("b")),
                  (Joint("ab", "fixed", "a", "b", Pose((1, 0, 0))),
                   Joint("ba", "fixed", "b", "a", Pose((1, 0, 0)))))
    poses = link_transforms(robot)
    assert np.allclose(poses["a"], np.identity(4)) and np.allclose(poses["b"], np.identity(4))
