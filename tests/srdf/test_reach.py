import math

import numpy as np
import pytest
from kinematics.robots import ARM, INERTIA, robot

from robotdesc.kinematics.geometry import collision_shapes
from robotdesc.model.tree import joint_motion
from robotdesc.spatial import pose_matrix
from robotdesc.srdf.reach import Sphere, joint_ranges, reach, spin_only, sweep

#: a base box; a wheel (cylinder along its spin axis y) on a continuous joint; an arm on a
#: limited revolute joint whose tip box can reach the base only when turned down; a far box
#: on a prismatic joint that never comes back.
ROVER = f"""<robot name="rover">
  <link name="base"><collision><geometry><box size="0.4 0.2 0.1"/></geometry></collision></link>
  <link name="wheel"><inertial><mass value="1"/>{INERTIA}</inertial><collision>
    <origin rpy="1.5707963 0 0"/><geometry><cylinder radius="0.05" length="0.02"/></geometry>
    </collision></link>
  <link name="wheel2"><inertial><mass value="1"/>{INERTIA}</inertial><collision>
    <origin rpy="1.5707963 0 0"/><geometry><cylinder radius="0.05" length="0.02"/></geometry>
    </collision></link>
  <link name="arm"><inertial><mass value="1"/>{INERTIA}</inertial>
    <collision><origin xyz="0.5 0 0"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="far"><inertial><mass value="1"/>{INERTIA}</inertial>
    <collision><geometry><sphere radius="0.05"/></geometry></collision></link>
  <joint name="w" type="continuous"><parent link="base"/><child link="wheel"/>
    <origin xyz="0.2 0.15 0"/><axis xyz="0 1 0"/></joint>
  <joint name="w2" type="continuous"><parent link="base"/><child link="wheel2"/>
    <origin xyz="0.28 0.15 0"/><axis xyz="0 1 0"/></joint>
  <joint name="a" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.6"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="1.6" effort="1" velocity="1"/></joint>
  <joint name="f" type="prismatic"><parent link="base"/><child link="far"/>
    <origin xyz="3 0 0"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/></joint>
</robot>"""


@pytest.mark.parametrize(("kind", "lower", "upper"), [("revolute", -0.3, 0.9),
                                                      ("revolute", -2.5, 2.0),
                                                      ("continuous", -math.pi, math.pi),
                                                      ("prismatic", -0.2, 0.7)])
def test_swept_sphere_holds_the_sphere_at_every_position(kind, lower, upper) -> None:
    limit = "" if kind == "continuous" else \
        f'<limit lower="{lower}" upper="{upper}" effort="1" velocity="1"/>'
    joint = robot(f"""<robot name="r"><link name="p"/><link name="c"/>
      <joint name="j" type="{kind}"><parent link="p"/><child link="c"/>
        <origin xyz="0.1 -0.2 0.3" rpy="0.3 0.2 0.1"/><axis xyz="1 2 3"/>{limit}</joint>
      </robot>""").joint("j")
    inner = Sphere((0.4, 0.1, -0.2), 0.05)
    outer = sweep(joint, inner, (lower, upper))
    for value in np.linspace(lower, upper, 50):
        moved = pose_matrix(joint.origin) @ joint_motion(joint, float(value))
        centre = moved[:3, :3] @ np.array(inner.centre) + moved[:3, 3]
        assert np.linalg.norm(centre - outer.centre) + inner.radius <= outer.radius + 1e-9


def test_pairs_that_cannot_meet_and_pairs_that_never_move() -> None:
    rover = robot(ROVER)
    shapes, _ = collision_shapes(rover, lambda mesh: None)
    swept = reach(rover, shapes)
    assert not swept.can_meet("base", "far")  # slides away, never back
    assert not swept.can_meet("wheel", "far")
    assert swept.can_meet("arm", "base")  # turned down by 1.6 rad it reaches the base
    assert swept.can_meet("wheel", "wheel2")
    assert swept.rigid("wheel", "wheel2")  # both only spin about their own axes
    assert swept.rigid("base", "wheel")
    assert not swept.rigid("arm", "wheel")


def test_spin_only_needs_geometry_symmetric_about_the_axis() -> None:
    rover = robot(ROVER)
    shapes, _ = collision_shapes(rover, lambda mesh: None)
    assert spin_only(rover, rover.joint("w"), shapes)
    assert not spin_only(rover, rover.joint("a"), shapes)  # the box is off the axis


def test_mimic_joints_get_the_range_of_their_driver() -> None:
    spans = joint_ranges(robot(ARM))
    assert spans["hand_joint"] == (0.1, 0.2)
    assert spans["hand_twin"] == pytest.approx((0.3, 0.5))  # 2 * q + 0.1
    assert spans["shoulder"] == (-math.pi, math.pi)
