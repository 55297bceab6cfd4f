"""The settle test: a unit slip in one link's inertia fails on that link; correct or
robotdesc-suggested inertias pass."""

from __future__ import annotations

import dataclasses

import pytest

pytest.importorskip("mujoco")

from robotdesc.errors import SimOptionError  # noqa: E402
from robotdesc.sim.hold import HoldOptions  # noqa: E402
from robotdesc.sim.run import SimOptions, settle_robot  # noqa: E402
from robotdesc.sim.settle import CHECKS, SettleOptions  # noqa: E402

from .fixture_robots import arm_urdf  # noqa: E402
from .sim_support import FIXTURES, load, with_suggested_inertias  # noqa: E402


def test_fixtures_are_current() -> None:
    assert (FIXTURES / "slip_arm.urdf").read_text() == arm_urdf()
    assert (FIXTURES / "slip_arm_unit_slip.urdf").read_text() == arm_urdf(slip=1e-6)


def test_unit_slip_fails_on_the_slipped_link() -> None:
    robot, meshes = load(FIXTURES / "slip_arm_unit_slip.urdf")
    report = settle_robot(robot, meshes)
    assert not report.passed
    assert report.culprit == "wrist_roll_link"
    for name in ("finite", "speed", "energy"):
        check = report.check(name)
        assert not check.passed and check.link == "wrist_roll_link", check
    assert report.check("finite").time < 0.5  # it blows up within the first half second
    assert report.settle_time is None


def test_correct_inertias_pass_and_settle() -> None:
    robot, meshes = load(FIXTURES / "slip_arm.urdf")
    report = settle_robot(robot, meshes)
    assert report.passed, report.failures
    assert [c.name for c in report.checks] == list(CHECKS)
    assert report.settle_time is not None and 0.05 < report.settle_time < 2.0


def test_robotdesc_suggested_inertias_pass() -> None:
    robot, meshes = load(FIXTURES / "slip_arm_unit_slip.urdf")
    fixed = with_suggested_inertias(robot)
    wrist = fixed.link("wrist_roll_link").inertial.inertia
    assert wrist.izz == pytest.approx(0.3 * 0.03 ** 2 / 2, rel=0.05)
    report = settle_robot(fixed, meshes)
    assert report.passed, report.failures


def test_the_servo_gains_follow_shape_not_written_inertia() -> None:
    robot, meshes = load(FIXTURES / "slip_arm_unit_slip.urdf")
    report = settle_robot(robot, meshes)
    wrist = next(i for i in report.inertias if i.joint == "wrist_roll")
    assert wrist.shape / wrist.written > 30  # what makes the loop unstable
    elbow = next(i for i in report.inertias if i.joint == "elbow")
    assert elbow.shape == pytest.approx(elbow.written, rel=0.2)


def test_passive_mode_runs_and_reports_every_check() -> None:
    robot, meshes = load(FIXTURES / "slip_arm.urdf")
    options = SimOptions(settle=SettleOptions(seconds=0.5, hold=HoldOptions(mode="passive")))
    report = settle_robot(robot, meshes, options)
    assert [c.name for c in report.checks] == list(CHECKS)
    assert report.check("finite").passed


def test_tight_joint_tolerance_reports_the_joint_and_its_link() -> None:
    robot, meshes = load(FIXTURES / "slip_arm.urdf")
    options = SimOptions(settle=SettleOptions(seconds=0.5, nudge=0.0, limit_tolerance=-1.0))
    report = settle_robot(robot, meshes, options)
    joints = report.check("joints")
    assert not joints.passed and "past its limit" in joints.message and joints.link


def test_options_are_validated() -> None:
    with pytest.raises(SimOptionError) as caught:
        SettleOptions(seconds=0)
    assert (caught.value.option, caught.value.value) == ("seconds", 0)
    with pytest.raises(SimOptionError, match="hold mode"):
        HoldOptions(mode="stiff")
    with pytest.raises(SimOptionError) as caught:
        dataclasses.replace(SimOptions(), collision="hand-made")
    assert caught.value.option == "collision"
