import json
import subprocess
import sys

import pytest

pytest.importorskip("pinocchio")

from kinematics.robots import ARM  # noqa: E402
from support import REPO  # noqa: E402


def run(*argv: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "robotdesc", "srdf", *argv],
                          capture_output=True, text=True, cwd=REPO, timeout=120)


def test_writes_srdf_and_report(tmp_path) -> None:
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    done = run(str(path), "--samples", "200", "--seed", "3", "-o", str(tmp_path / "arm.srdf"))
    assert done.returncode == 0, done.stderr
    assert 'link1="base" link2="fore" reason="Default"' in (tmp_path / "arm.srdf").read_text()
    report = json.loads((tmp_path / "arm.collisions.json").read_text())
    assert report["samples"] == 200 and report["seed"] == 3


def test_refuses_to_overwrite_its_input(tmp_path) -> None:
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    done = run(str(path), "--samples", "10", "-o", str(path))
    assert done.returncode == 2 and "refusing" in done.stderr
    assert path.read_text() == ARM


def test_a_robot_without_moving_joints_gets_its_adjacent_pairs(tmp_path) -> None:
    """No joint to sample (a fixed-only robot) is a matrix of adjacent pairs, not exit 3."""
    path = tmp_path / "fixed.urdf"
    box = '<collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>'
    path.write_text(f'<robot name="fixed"><link name="base">{box}</link><link name="b">{box}'
                    '</link><joint name="j" type="fixed"><parent link="base"/><child link="b"/>'
                    '</joint></robot>')
    done = run(str(path), "--samples", "20", "-o", str(tmp_path / "fixed.srdf"))
    assert done.returncode == 0, done.stderr
    assert 'link1="b" link2="base" reason="Adjacent"' in (tmp_path / "fixed.srdf").read_text()
