"""`robotdesc sim FILE`: pass/fail per check, settle time, real-time factors; exit codes."""

from __future__ import annotations

import pytest

pytest.importorskip("mujoco")

from robotdesc.cli import main  # noqa: E402

from .sim_support import FIXTURES  # noqa: E402


def test_failing_robot_exits_1_and_names_the_link(capsys) -> None:
    code = main(["sim", str(FIXTURES / "slip_arm_unit_slip.urdf"), "--seconds", "1",
                 "--no-rtf"])
    out = capsys.readouterr().out
    assert code == 1
    assert "FAIL  finite" in out and "'wrist_roll_link'" in out
    assert "result: FAIL (link 'wrist_roll_link')" in out


@pytest.mark.slow  # settles, then generates collision (method auto) and times both
def test_passing_robot_prints_checks_settle_time_and_rtf(capsys) -> None:
    code = main(["sim", str(FIXTURES / "slip_arm.urdf"), "--seconds", "0.5",
                 "--drop-height", "0.02"])
    out = capsys.readouterr().out
    assert code == 0, out
    for name in ("finite", "energy", "joints", "speed"):
        assert f"PASS  {name}" in out
    assert "dropped from 0.02 m" in out and "settle time:" in out
    assert "collision as-is" in out and "real-time factor" in out
    assert "ratio generated / as-is" in out or "generated collision unavailable" in out


def test_bad_arguments_exit_2(capsys) -> None:
    assert main(["sim", str(FIXTURES / "slip_arm.urdf"), "--seconds", "0"]) == 2
    assert main(["sim", str(FIXTURES / "slip_arm.urdf"), "--collision", "magic"]) == 2
