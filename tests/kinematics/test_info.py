import json
import subprocess
import sys

import pytest

pytest.importorskip("pinocchio")

from support import REPO

from kinematics.robots import ARM, robot
from robotdesc.errors import UsageError
from robotdesc.kinematics.info import robot_info


def test_counts_mass_and_centre_of_mass() -> None:
    info = robot_info(robot(ARM))
    assert info.links == 6 and dict(info.joints_by_type)["prismatic"] == 2
    assert info.dof == 3 and [m.joint for m in info.mimic] == ["hand_twin"]
    assert info.total_mass == pytest.approx(8.5)
    # upper's COM is 0.1 above its frame (z 0.3); fore and hand sit at z 0.6 and 0.8 at zero
    expected_z = (5 * 0 + 2 * 0.4 + 1 * 0.6 + 0.5 * 0.8) / 8.5
    assert info.com_zero[2] == pytest.approx(expected_z)
    assert info.bounds[0][2] == pytest.approx(-0.2)


def test_centre_of_mass_at_a_configuration() -> None:
    info = robot_info(robot(ARM), positions={"hand_joint": 0.2})
    assert info.com_at[2] - info.com_zero[2] == pytest.approx(0.5 * 0.2 / 8.5)
    assert dict(info.configuration)["hand_twin"] == pytest.approx(0.5)


def test_unknown_joint_in_positions_is_a_usage_error() -> None:
    with pytest.raises(UsageError, match="hand_twin"):
        robot_info(robot(ARM), positions={"hand_twin": 0.2})


def test_info_command_prints_json(tmp_path) -> None:
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    done = subprocess.run([sys.executable, "-m", "robotdesc", "info", str(path), "--format",
                           "json", "--q", "elbow=0.3"], check=False, capture_output=True, text=True,
                          cwd=REPO, timeout=120)
    assert done.returncode == 0, done.stderr
    report = json.loads(done.stdout)
    assert report["dof"] == 3 and report["configuration"]["elbow"] == 0.3
    bad = subprocess.run([sys.executable, "-m", "robotdesc", "info", str(path), "--q", "elbow"],
                         check=False, capture_output=True, text=True, cwd=REPO, timeout=120)
    assert bad.returncode == 2 and "JOINT=VALUE" in bad.stderr


@pytest.mark.parametrize("value", ["inf", "nan", "-inf"])
def test_info_refuses_a_position_that_is_no_finite_number(tmp_path, value) -> None:
    """`--q elbow=nan` printed (nan, nan, nan) and bare NaN in JSON, exit 0 (held-out)."""
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    done = subprocess.run([sys.executable, "-m", "robotdesc", "info", "--q", f"elbow={value}",
                           str(path), "--format", "json"], check=False, capture_output=True,
                          text=True, cwd=REPO, timeout=120)
    assert done.returncode == 2 and "JOINT=VALUE" in done.stderr and not done.stdout


def test_collision_meshes_that_do_not_resolve_are_named_not_hidden() -> None:
    """Both links had <collision> meshes that do not resolve, and info said only "no
    collision geometry" (held-out: solo12 with its package misnamed)."""
    text = ('<robot name="two"><link name="a"><collision><geometry><mesh filename='
            '"package://gone/a.stl"/></geometry></collision></link></robot>')
    info = robot_info(robot(text))
    assert info.bounds is None
    assert len(info.left_out) == 1 and info.left_out[0].startswith("link 'a': ")
    assert info.to_dict()["left_out"] == list(info.left_out)
