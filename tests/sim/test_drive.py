"""The drive test on a small four-wheel rover built here: configuration, kinematics, and
achieved against commanded velocity in MuJoCo (and DART, slow)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from robotdesc.cli import main
from robotdesc.errors import DriveConfigError
from robotdesc.sim.drive import (
    DriveCommand,
    DriveGroup,
    DriveOptions,
    commands,
    groups_from_config,
    resolve_groups,
    wheel_signs,
    wheel_targets,
)

from .drive_robot import TRACK, WHEEL_RADIUS, rover_urdf
from .sim_support import load


def test_groups_come_from_the_sibling_control_package(tmp_path) -> None:
    path = rover_urdf(tmp_path)
    (group,) = groups_from_config(str(path))
    assert group.name == "diff_drive"
    assert group.left == ("left_front_wheel", "left_rear_wheel")
    assert group.separation == TRACK and group.radius == WHEEL_RADIUS


def test_ros1_config_and_multipliers(tmp_path) -> None:
    config = tmp_path / "tracks.yaml"
    config.write_text("base:\n  type: diff_drive_controller/DiffDriveController\n"
                      "  left_wheel: a\n  right_wheel: [b, c]\n  wheel_separation: 0.5\n"
                      "  wheel_separation_multiplier: 2.0\n")
    (group,) = groups_from_config("unused.urdf", [str(config)])
    assert (group.name, group.left, group.right) == ("base", ("a",), ("b", "c"))
    assert group.separation_multiplier == 2.0 and group.radius is None


def test_sizes_and_signs_are_found_from_the_model(tmp_path) -> None:
    robot, _ = load(rover_urdf(tmp_path, with_config=False))
    (group,) = resolve_groups(robot, [DriveGroup("g", ("left_front_wheel", "left_rear_wheel"),
                                                 ("right_front_wheel", "right_rear_wheel"))])
    assert group.radius == pytest.approx(WHEEL_RADIUS)
    assert group.separation == pytest.approx(TRACK)
    signs = wheel_signs(robot, group.left + group.right)
    assert set(signs.values()) == {1.0}  # axis +y rolls toward +x
    spin = wheel_targets([group], signs, DriveCommand("spin", 0.0, 1.0))
    assert spin["left_front_wheel"] == pytest.approx(-TRACK / 2 / WHEEL_RADIUS)
    assert spin["right_rear_wheel"] == pytest.approx(TRACK / 2 / WHEEL_RADIUS)
    straight, turn, arc = commands([group], DriveOptions(speed=0.2))
    assert turn.angular == pytest.approx(0.4 / TRACK) and arc.angular == pytest.approx(0.2 / TRACK)
    with pytest.raises(DriveConfigError):
        resolve_groups(robot, [DriveGroup("g", ("nope",), ("right_front_wheel",))])
    with pytest.raises(DriveConfigError):
        resolve_groups(robot, [])


def test_rover_drives_as_commanded_in_mujoco(tmp_path, capsys) -> None:
    pytest.importorskip("mujoco")
    path = rover_urdf(tmp_path)
    code = main(["sim", str(path), "--drive", "--format", "json"])
    report = json.loads(capsys.readouterr().out)["drive"]
    by_name = {r["command"]: r for r in report["results"]}
    assert by_name["straight"]["passed"], by_name
    assert by_name["straight"]["achieved_linear"] == pytest.approx(0.2, rel=0.3)
    assert by_name["arc"]["achieved_linear"] == pytest.approx(0.2, rel=0.3)
    # skid steering under-turns (the wheels slide sideways); the sign must be right
    assert by_name["arc"]["achieved_angular"] > 0 and by_name["spin"]["achieved_angular"] > 0
    assert code == (0 if report["passed"] else 1)


def test_config_sets_the_separation_multiplier_per_engine(tmp_path, capsys) -> None:
    pytest.importorskip("mujoco")
    path = rover_urdf(tmp_path)
    config = path.parent / "robotdesc.toml"
    config.write_text("[sim]\nseparation-multiplier = { mujoco = 1.5 }\n")
    main(["sim", str(path), "--drive", "--format", "json"])
    groups = json.loads(capsys.readouterr().out)["drive"]["groups"]
    assert [g["separation_multiplier"] for g in groups] == [1.5]
    config.write_text("[sim]\nseparation-multiplier = { bullet = 1.5 }\n")
    assert main(["sim", str(path), "--drive"]) == 2
    assert "unknown engine 'bullet'" in capsys.readouterr().err


def test_drive_without_configuration_says_how_to_give_the_wheels(tmp_path, capsys) -> None:
    pytest.importorskip("mujoco")
    path = rover_urdf(tmp_path, with_config=False)
    assert main(["sim", str(path), "--drive"]) == 2
    assert "--left-wheels" in capsys.readouterr().err


@pytest.mark.slow
def test_rover_drives_as_commanded_in_dart(tmp_path, capsys) -> None:
    pytest.importorskip("dartpy")
    path = rover_urdf(tmp_path)
    code = main(["sim", str(path), "--drive", "--engine", "dart", "--left-wheels",
                 "left_front_wheel,left_rear_wheel", "--right-wheels",
                 "right_front_wheel,right_rear_wheel"])
    out = capsys.readouterr().out
    assert "PASS  straight" in out, out
    assert code in (0, 1)


def test_wheels_without_an_effort_limit_drive_as_commanded(tmp_path, capsys) -> None:
    """Continuous wheel joints usually carry no `<limit>` (TurtleBot 3): the servo must still
    track, not rattle (a 1 kg two-wheeler spun at 16.7 rad/s when told 2.5). MuJoCo comes
    with the test extra, so this test is not skipped."""
    path = Path(__file__).with_name("two_wheeler_no_effort.urdf")
    code = main(["sim", str(path), "--drive", "--left-wheels", "wheel_left_joint",
                 "--right-wheels", "wheel_right_joint", "--no-rtf", "--format", "json"])
    report = json.loads(capsys.readouterr().out)["drive"]
    by_name = {r["command"]: r for r in report["results"]}
    assert by_name["straight"]["achieved_linear"] == pytest.approx(0.2, rel=0.1)
    assert by_name["spin"]["achieved_angular"] == pytest.approx(2.5, rel=0.3)
    assert code == 0 and report["passed"]
