"""The engine registry, the DART install hint, and the engines' shared interface."""

from __future__ import annotations

import sys

import pytest

from robotdesc.cli import main
from robotdesc.errors import SimOptionError, SimUnavailable
from robotdesc.sim import backend
from robotdesc.sim.backend import DART_INSTALL_HINT, DART_REQUIREMENT
from robotdesc.sim.compare import parse_variants
from robotdesc.sim.engine import ENGINES, engine

from .sim_support import FIXTURES


def test_registry_names_both_engines_with_their_time_steps() -> None:
    assert set(ENGINES) == {"mujoco", "dart"}
    assert engine("dart").default_timestep == 0.001  # Gazebo's
    with pytest.raises(SimOptionError, match="unknown engine"):
        engine("ode")


def test_missing_dartpy_gives_the_install_hint_and_exit_2(monkeypatch, capsys) -> None:
    monkeypatch.setitem(sys.modules, "dartpy", None)  # makes `import dartpy` fail
    with pytest.raises(SimUnavailable) as caught:
        backend.import_dartpy()
    assert (caught.value.engine, caught.value.requirement) == ("dart", DART_REQUIREMENT)
    assert "pip install '.[dart]'" in DART_INSTALL_HINT
    code = main(["sim", str(FIXTURES / "slip_arm.urdf"), "--engine", "dart"])
    captured = capsys.readouterr()
    assert code == 2
    assert "pip install '.[dart]'" in captured.err and "Traceback" not in captured.err


def test_compare_variants_are_checked(capsys) -> None:
    assert parse_variants("visual, generated") == ("visual", "generated")
    with pytest.raises(SimOptionError, match="unknown: magic"):
        parse_variants("visual,magic")
    assert main(["sim", str(FIXTURES / "slip_arm.urdf"), "--compare", "magic"]) == 2


@pytest.mark.parametrize("name", ["mujoco", "dart"])
def test_scene_interface_on_a_small_arm(name) -> None:
    pytest.importorskip("mujoco" if name == "mujoco" else "dartpy")
    from robotdesc.sim.scene import SceneOptions

    from .sim_support import load

    robot, meshes = load(FIXTURES / "slip_arm.urdf")
    scene = engine(name).build(robot, meshes, SceneOptions(timestep=0.002, drop_height=0.05))
    assert scene.geoms == 7 and scene.triangles == 0  # primitives only
    assert scene.lowest_point() == pytest.approx(0.05, abs=1e-6)
    scene.step(100)
    assert scene.time == pytest.approx(0.2) and scene.finite()
    assert scene.lowest_point() < 0.01  # it fell onto the ground
    assert scene.collision_seconds() >= 0
    scene.reset()
    assert scene.time == 0 and scene.lowest_point() == pytest.approx(0.05, abs=1e-6)
