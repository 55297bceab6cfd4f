"""A worker started ahead of its job (`launch.start_early`): a cold lint uses it, an unused
one is killed, and only the process that started it hands it a job."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from robotdesc.cli import main
from robotdesc.expansion import ExpandOptions, expand_file, launch

WS = Path(__file__).parent / "fixtures" / "ws"


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    shutil.copytree(WS, tmp_path / "ws")
    return tmp_path / "ws" / "src"


@pytest.fixture
def launches(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """The pids of the workers started in this test (the early one included)."""
    started: list[int] = []
    real = launch.launch

    def counting():
        proc = real()
        started.append(proc.pid)
        return proc

    monkeypatch.setattr(launch, "launch", counting)
    yield started
    launch.drop_early()


def _gone(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    return False


def test_a_cold_lint_expands_in_the_worker_it_started_early(workspace, launches, monkeypatch,
                                                            capsys) -> None:
    early: list[int] = []
    real = launch.start_early
    monkeypatch.setattr(launch, "start_early", lambda: early.append(1) or real())
    robot = workspace / "robot_pkg" / "urdf" / "robot.urdf.xacro"
    code = main(["lint", str(robot), "--no-cache", "--select", "J"])
    assert code in (0, 1)
    assert early  # by the command line (--no-cache), again (a no-op) when the lint starts
    assert len(launches) == 1  # the early worker did the expansion: no second start
    assert not launch._EARLY and _gone(launches[0])


@pytest.mark.parametrize("words", [["--select", "NO_SUCH_RULE"], ["--format", "nope"]])
def test_a_command_that_ends_before_expanding_ends_its_early_worker(workspace, launches, words,
                                                                   capsys) -> None:
    robot = workspace / "robot_pkg" / "urdf" / "robot.urdf.xacro"
    assert main(["lint", str(robot), "--no-cache", *words]) == 2
    assert len(launches) == 1 and _gone(launches[0]) and not launch._EARLY


def test_expand_with_no_cache_uses_the_early_worker(workspace, launches, capsys) -> None:
    robot = workspace / "robot_pkg" / "urdf" / "robot.urdf.xacro"
    assert main(["expand", str(robot), "--no-cache"]) == 0
    assert b"<robot" in capsys.readouterr().out.encode()
    assert len(launches) == 1 and _gone(launches[0])


def test_no_early_worker_for_a_plain_urdf(launches, tmp_path, capsys) -> None:
    urdf = tmp_path / "plain.urdf"
    urdf.write_text('<robot name="p"><link name="a"/></robot>')
    main(["lint", str(urdf), "--no-cache"])
    assert launches == []


def test_each_target_of_a_lint_expands_in_a_worker_started_before_its_turn(
        workspace, launches, monkeypatch, capsys) -> None:
    robot = workspace / "robot_pkg" / "urdf" / "robot.urdf.xacro"
    second = robot.with_name("second.urdf.xacro")
    second.write_text(robot.read_text())
    taken: list[bool] = []
    real = launch.take_early

    def taking():
        proc = real()
        taken.append(proc is not None)
        return proc

    monkeypatch.setattr(launch, "take_early", taking)
    assert main(["lint", str(robot), str(second), "--no-cache", "--select", "J"]) in (0, 1)
    assert taken == [True, True]  # each expansion found its worker running
    assert len(launches) == 2
    assert all(_gone(pid) for pid in launches) and not launch._EARLY


def test_an_early_worker_no_expansion_takes_is_killed(workspace, launches) -> None:
    launch.start_early()
    launch.start_early()  # one at a time
    assert len(launches) == 1
    launch.drop_early()
    assert _gone(launches[0]) and not launch._EARLY


def test_the_early_worker_expands_like_a_new_one(workspace, launches) -> None:
    robot = workspace / "robot_pkg" / "urdf" / "robot.urdf.xacro"
    options = ExpandOptions(use_cache=False)
    fresh = expand_file(robot, {"length": "0.3"}, options=options)
    launch.start_early()
    early = expand_file(robot, {"length": "0.3"}, options=options)
    assert len(launches) == 2 and early == fresh


def test_another_process_never_takes_the_early_worker(workspace, launches,
                                                      monkeypatch) -> None:
    launch.start_early()
    monkeypatch.setattr(launch.os, "getpid", lambda: -1)  # as in a forked child
    assert launch.take_early() is None
    monkeypatch.undo()
    taken = launch.take_early()
    assert taken is not None
    launch.kill_group(taken)
