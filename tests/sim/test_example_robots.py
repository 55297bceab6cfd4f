"""Real robots from example-robot-data: an arm, a quadruped, humanoids; outcomes pinned."""

from __future__ import annotations

import pytest

pytest.importorskip("mujoco")

from robotdesc.sim.run import settle_robot  # noqa: E402

from .sim_support import ERD, load  # noqa: E402

PASSING = {
    "arm ur5": "robots/ur_description/urdf/ur5_robot.urdf",
    "quadruped go2": "robots/go2_description/urdf/go2.urdf",
    "quadruped solo12": "robots/solo_description/robots/solo12.urdf",
    "humanoid talos": "robots/talos_data/robots/talos_reduced.urdf",
}


@pytest.mark.parametrize("path", PASSING.values(), ids=PASSING.keys())
def test_passes_every_check(erd_options, path) -> None:
    report = settle_robot(*load(ERD / path, erd_options))
    assert report.passed, report.failures


def test_quadruped_comes_to_rest(erd_options) -> None:
    report = settle_robot(*load(ERD / PASSING["quadruped go2"], erd_options))
    assert report.settle_time is not None and report.settle_time < 1.8


def test_icub_fails_on_its_massless_moving_hip(erd_options) -> None:
    """icub's r_hip_1 is driven by a joint yet carries no mass: MuJoCo cannot move it."""
    report = settle_robot(*load(ERD / "robots/icub_description/robots/icub.urdf", erd_options))
    assert not report.passed
    model = report.check("model")
    assert model.link == "r_hip_1"
    assert "mass and inertia of moving bodies" in model.message


def test_human_model_fails_on_its_virtual_joint_link(erd_options) -> None:
    report = settle_robot(*load(ERD / "robots/human_description/robots/human.urdf",
                                erd_options))
    assert report.culprit == "left_upperleg_virtual"
