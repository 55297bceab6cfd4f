"""Real-time factor: positive, and visual meshes as collision cost more than the STL hulls."""

from __future__ import annotations

import pytest

pytest.importorskip("mujoco")

from robotdesc.sim.run import SimOptions, compare_rtf  # noqa: E402
from robotdesc.sim.settle import SettleOptions  # noqa: E402

from .sim_support import ERD, FIXTURES, load  # noqa: E402

SHORT = SimOptions(settle=SettleOptions(seconds=0.2))


def test_rtf_of_primitives_is_positive() -> None:
    comparison = compare_rtf(*load(FIXTURES / "slip_arm.urdf"), SHORT, candidate=None)
    assert comparison.baseline.rtf > 0 and comparison.baseline.geoms == 7
    assert comparison.ratio is None


def test_visual_collision_has_more_mesh_vertices(erd_options) -> None:
    robot, meshes = load(ERD / "robots/ur_description/urdf/ur5_robot.urdf", erd_options)
    comparison = compare_rtf(robot, meshes, SHORT, baseline="visual", candidate="as-is")
    assert comparison.baseline.mesh_vertices > comparison.candidate.mesh_vertices
    assert comparison.ratio is not None and comparison.ratio > 0
