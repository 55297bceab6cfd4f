"""Triangle collision: a torus dropped over a thin pole falls through its hole in DART (which
collides the mesh's triangles, as Gazebo) and rests on the pole in MuJoCo (which collides the
mesh's convex hull)."""

from __future__ import annotations

import pytest

from robotdesc.sim.engine import engine
from robotdesc.sim.scene import SceneOptions

from .drive_robot import torus_over_pole_urdf
from .sim_support import load

TUBE, POLE_TOP = 0.02, 0.3


def _settled_height(name: str, tmp_path) -> float:
    robot, meshes = load(torus_over_pole_urdf(tmp_path, minor=TUBE, pole_height=POLE_TOP))
    chosen = engine(name)
    scene = chosen.build(robot, meshes, SceneOptions(timestep=chosen.default_timestep,
                                                     self_collision=True))
    scene.step(round(0.8 / scene.timestep))
    return float(scene.link_position("torus")[2])


@pytest.mark.slow
def test_dart_torus_falls_over_the_pole_to_the_ground(tmp_path) -> None:
    pytest.importorskip("dartpy")
    assert _settled_height("dart", tmp_path) == pytest.approx(TUBE, abs=0.005)


def test_mujoco_torus_rests_on_the_pole_through_its_hull(tmp_path) -> None:
    pytest.importorskip("mujoco")
    assert _settled_height("mujoco", tmp_path) == pytest.approx(POLE_TOP + TUBE, abs=0.01)
