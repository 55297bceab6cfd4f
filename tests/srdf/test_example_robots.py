"""Acceptance on example-robot-data: every pair robotdesc disables as Adjacent or Default is
disabled in the robot's published SRDF too, except the differences listed here."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("pinocchio")

from support import REPO, example_robot_data_dir  # noqa: E402

import robotdesc  # noqa: E402
from robotdesc.mesh.locate import MeshLocator  # noqa: E402
from robotdesc.srdf.matrix import Reason, compute_matrix, default_collisions, prepare_scene  # noqa: E402

ROBOTS = example_robot_data_dir()
pytestmark = pytest.mark.skipif(ROBOTS is None, reason="example-robot-data is not installed")

#: (URDF, published SRDF, pairs robotdesc disables as Adjacent/Default that the SRDF keeps).
CASES = [
    ("panda_description/urdf/panda.urdf", "panda_description/srdf/panda.srdf", set()),
    # ur5.srdf predates the ee_link collision box: wrist_3_link carries ee_link (Adjacent);
    # ee_link is welded to wrist_3_link, so one body with it, adjacent to wrist_2_link.
    ("ur_description/urdf/ur5_robot.urdf", "ur_description/srdf/ur5.srdf",
     {("ee_link", "wrist_3_link"), ("ee_link", "wrist_2_link")}),
    ("ur_description/urdf/ur5_gripper.urdf", "ur_description/srdf/ur5_gripper.srdf", set()),
    ("ur_description/urdf/ur3_gripper.urdf", "ur_description/srdf/ur3_gripper.srdf", set()),
    ("ur_description/urdf/ur5_joint_limited_robot.urdf",
     "ur_description/srdf/ur5_joint_limited_robot.srdf", set()),
]
PAIR = re.compile(r'link1="([^"]+)"\s+link2="([^"]+)"(?:\s+reason="([^"]+)")?')


def published(srdf: str) -> dict[tuple[str, str], str | None]:
    text = (ROBOTS / srdf).read_text(encoding="utf-8")
    return {tuple(sorted((a, b))): reason or None for a, b, reason in PAIR.findall(text)}


def mesh_path(urdf: Path, robot):
    # the URDFs say package://example-robot-data/...: the share folder is that package
    return MeshLocator.for_robot(robot, package_map=(
        ("example-robot-data", str(ROBOTS.parent)),), origin=str(urdf)).path


@pytest.mark.parametrize(("urdf", "srdf", "differences"), CASES, ids=[c[0] for c in CASES])
def test_adjacent_and_default_pairs_are_disabled_in_the_published_srdf(urdf, srdf,
                                                                       differences) -> None:
    path = ROBOTS / urdf
    robot = robotdesc.load(str(path))
    prepared = prepare_scene(robot, mesh_path(path, robot))
    ours = set(prepared.adjacent) | set(default_collisions(prepared))
    assert ours - set(published(srdf)) == differences


#: Links welded by fixed joints are one body (issue 14, item 2): the hand, welded to link7
#: through link8, is adjacent to link6, and the fingers, joined to the hand, to link7. The
#: published SRDF disables these pairs too, as "Never".
PANDA_WELDED_ADJACENT = {("panda_hand", "panda_link6"), ("panda_leftfinger", "panda_link7"),
                         ("panda_link7", "panda_rightfinger")}


def test_panda_adjacent_and_default_reasons_match_exactly() -> None:
    path = ROBOTS / CASES[0][0]
    robot = robotdesc.load(str(path))
    prepared = prepare_scene(robot, mesh_path(path, robot))
    theirs = published(CASES[0][1])
    assert set(prepared.adjacent) - PANDA_WELDED_ADJACENT \
        == {p for p, r in theirs.items() if r == "Adjacent"}
    assert all(theirs[pair] == "Never" for pair in PANDA_WELDED_ADJACENT)
    assert set(default_collisions(prepared)) == {p for p, r in theirs.items() if r == "Default"}


@pytest.mark.slow
def test_panda_full_matrix_matches_the_published_srdf() -> None:
    path = ROBOTS / CASES[0][0]
    robot = robotdesc.load(str(path))
    matrix = compute_matrix(robot, mesh_path(path, robot), samples=10000, seed=1, workers=2)
    ours = {(p.link1, p.link2): p.reason.value for p in matrix.disabled()}
    theirs = published(CASES[0][1])
    # the same 35 pairs, and the same reasons but for the welded-body pairs: Adjacent for
    # robotdesc, Never in the published file
    assert ours == {pair: "Adjacent" if pair in PANDA_WELDED_ADJACENT else reason
                    for pair, reason in theirs.items()}


@pytest.mark.slow
def test_srdf_command_same_seed_same_file(tmp_path) -> None:
    urdf = ROBOTS / "ur_description/urdf/ur5_robot.urdf"
    outputs = []
    for name in ("a.srdf", "b.srdf"):
        done = subprocess.run([sys.executable, "-m", "robotdesc", "srdf", str(urdf), "--samples",
                               "3000", "--seed", "4", "-o", str(tmp_path / name)],
                              capture_output=True, text=True, cwd=REPO, timeout=300,
                              env={**__import__("os").environ,
                                   "AMENT_PREFIX_PATH": str(ROBOTS.parents[2])})
        assert done.returncode == 0, done.stderr
        outputs.append((tmp_path / name).read_text())
    assert outputs[0] == outputs[1] and 'reason="Adjacent"' in outputs[0]
    assert (tmp_path / "a.collisions.json").is_file()
    assert Reason.NEVER.value in outputs[0]
