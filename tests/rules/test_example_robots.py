"""All rules over the real example-robot-data URDFs: nothing crashes, and a few genuine
problems in those files are found where they are."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import pytest
from support import example_robot_data_dir, example_robot_urdfs

from robotdesc.diagnostics import Finding
from robotdesc.model.parse import parse_urdf
from robotdesc.rules.catalog import all_rules
from robotdesc.rules.registry import RuleContext, run_rule

ROBOTS = example_robot_data_dir()
URDFS = example_robot_urdfs()
pytestmark = pytest.mark.skipif(not URDFS, reason="example-robot-data is not installed")


def lint(name: str) -> list[tuple[str, Finding]]:
    [path] = [p for p in URDFS if p.name == name]
    robot = parse_urdf(path.read_bytes(), str(path))
    return [(rule_.code, finding) for rule_ in all_rules()
            for finding in run_rule(rule_, robot, RuleContext(options=rule_.default_options()))]


def located(name: str, code: str) -> set[tuple[str, int]]:
    return {(f.element, f.where.span.line) for c, f in lint(name) if c == code}


def test_there_are_many_example_robots() -> None:
    assert len(URDFS) >= 60


@pytest.mark.parametrize("path", URDFS, ids=lambda p: p.name)
def test_all_rules_run_on_example_robot(path: Path) -> None:
    robot = parse_urdf(path.read_bytes(), str(path))
    for rule_ in all_rules():
        for finding in run_rule(rule_, robot, RuleContext(options=rule_.default_options())):
            assert finding.where is not None and finding.where.span.line > 0
            assert finding.message and finding.element


def test_clean_example_robots_stay_clean() -> None:
    for name in ("ur5_robot.urdf", "solo12.urdf"):
        assert lint(name) == [], name


def test_go1_calf_limits_exclude_zero_and_its_base_tensor_is_singular() -> None:
    """The trunk.dae (a 28 MB COLLADA) is read now; the base's rank-1 tensor is I103's."""
    assert Counter(code for code, _ in lint("go1.urdf")) == Counter({"K102": 4, "I103": 1,
                                                                   "K104": 1})


def test_panda_joint4_limits_exclude_the_zero_configuration() -> None:
    """And at that pose (joint 4 mid-range, fingers closed) the collision meshes of the
    hand, link 5 and link 7 overlap; the fingers touch only because they are closed at
    their limit, which K203 reports with the SRDF reason "Default"."""
    assert located("panda.urdf", "K102") == {("joint:panda_joint4", 124)}
    collide = {finding.message.split(" collide")[0]
               for code, finding in lint("panda.urdf") if code == "K201"}
    assert collide == {"links 'panda_hand' and 'panda_link5'",
                       "links 'panda_link5' and 'panda_link7'"}
    [at_limit] = [f for code, f in lint("panda.urdf") if code == "K203"]
    assert 'link1="panda_leftfinger" link2="panda_rightfinger" reason="Default"' in at_limit.fix
    assert Counter(code for code, _ in lint("panda.urdf")) == Counter(
        {"K102": 1, "K201": 2, "K203": 1, "C105": 1})


def test_z1_links_without_collision_and_folded_at_its_limits() -> None:
    """z1's zero pose is folded against joint limits: link02/link06 touch there and part
    once the joints move inward (K203, "Default"), not a K201 overlap."""
    assert Counter(code for code, _ in lint("z1.urdf")) == Counter({"M115": 2, "K203": 1,
                                                                   "S203": 1})


def test_ur3_urdf_is_an_empty_robot_without_a_name() -> None:
    codes = Counter(code for code, _ in lint("ur3.urdf"))
    assert codes == Counter({"S001": 1, "S110": 1})


def test_tiago_dual_gazebo_reference_left_unexpanded() -> None:
    assert ("gazebo:wheel_{side}_joint", 346) in located("tiago_dual.urdf", "G101")


def test_alex_hand_mimics_an_unprefixed_joint() -> None:
    assert ("joint:Left_index_q2", 1037) in located("alex_psyonic_hands.urdf", "J201")


def test_talos_reduced_corrected_uses_undefined_material() -> None:
    assert located("talos_reduced_corrected.urdf", "V101") == {
        ("link:wrist_right_ft_tool_link/visual[0]", 1233),
        ("link:wrist_left_ft_tool_link/visual[0]", 1287)}


def test_talos_left_arm_refers_to_the_missing_first_arm_joint() -> None:
    assert located("talos_left_arm.urdf", "T101") == {("transmission:arm_left_1_trans", 353)}
    assert ("gazebo:arm_left_1_joint", 163) in located("talos_left_arm.urdf", "G101")


def test_talos_gripper_fixed_joints_carry_mimic() -> None:
    findings = [f for c, f in lint("talos_reduced.urdf") if c == "J203"]
    assert len(findings) == 12
    assert all(f.message.startswith("fixed joint") for f in findings)


def test_mesh_uri_problems() -> None:
    # 20 file:// URIs of one machine's NAOqi SDK: one problem, one finding that counts them
    [uris] = [f for c, f in lint("romeo_laas_small.urdf") if c == "P102"]
    assert uris.message.endswith(", and 19 more mesh references under "
                                 "'/usr/Romeo/naoqi-sdk-2.3.0.14-linux64/share/alrobotmodel/"
                                 "meshes/romeo'")
    assert Counter(c for c, _ in lint("talos_full_v2.urdf"))["P104"] == 93
