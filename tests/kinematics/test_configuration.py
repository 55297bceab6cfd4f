import math

from kinematics.robots import ARM, robot
from robotdesc.kinematics.configuration import (
    default_configuration,
    follow_mimics,
    joint_range,
    zero_configuration,
)


def test_default_is_zero_inside_the_limits_else_the_middle() -> None:
    arm = robot(ARM)
    default = default_configuration(arm)
    assert default["elbow"] == 0.0 and default["shoulder"] == 0.0
    assert math.isclose(default["hand_joint"], 0.15)
    assert math.isclose(default["hand_twin"], 2 * 0.15 + 0.1)


def test_zero_configuration_moves_mimic_joints_by_their_offset() -> None:
    assert zero_configuration(robot(ARM))["hand_twin"] == 0.1


def test_mimic_chains_follow_and_cycles_get_zero() -> None:
    chain = robot("""<robot name="r"><link name="a"/><link name="b"/><link name="c"/><link name="d"/>
      <joint name="j1" type="continuous"><parent link="a"/><child link="b"/></joint>
      <joint name="j2" type="continuous"><parent link="b"/><child link="c"/><mimic joint="j1" multiplier="2"/></joint>
      <joint name="j3" type="continuous"><parent link="c"/><child link="d"/><mimic joint="j2" offset="1"/></joint>
    </robot>""")
    assert follow_mimics(chain, {"j1": 0.5, "j3": 9.0}) == {"j1": 0.5, "j2": 1.0, "j3": 2.0}
    loop = robot("""<robot name="r"><link name="a"/><link name="b"/><link name="c"/>
      <joint name="j1" type="continuous"><parent link="a"/><child link="b"/><mimic joint="j2"/></joint>
      <joint name="j2" type="continuous"><parent link="b"/><child link="c"/><mimic joint="j1"/></joint>
    </robot>""")
    assert follow_mimics(loop, {}) == {"j1": 0.0, "j2": 0.0}


def test_range_of_continuous_and_unusable_limits() -> None:
    arm = robot(ARM)
    assert joint_range(arm.joint("shoulder")).bounded is False
    bad = robot('<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="revolute">'
                '<parent link="a"/><child link="b"/><limit lower="1" upper="0" effort="1" '
                'velocity="1"/></joint></robot>')
    assert joint_range(bad.joint("j")) is None
