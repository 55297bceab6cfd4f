"""A worker started ahead of its job (`runner.start_early`): a cold lint uses it, an unused
one is killed, and only the process that started it hands it a job."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from robotdesc.cli import main
from robotdesc.expansion import ExpandOptions, expand_file, runner

WS = Path(__file__).parent / "fixtures" / "ws"


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    shutil.copytree(WS, tmp_path / "ws")
    return tmp_path / "ws" / "src"


@pytest.fixture
def launches(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """The pids of the workers started in this test (the early one included)."""
    started: list[int] = []
    real = runner._launch

    def counting():
        proc = real()
        started.append(proc.pid)
        return proc

    monkeypatch.setattr(runner, "_launch", counting)
    yield started
    runner.drop_early()


def _gone(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    return False


def test_a_cold_lint_expands_in_the_worker_it_started_early(workspace, launches, monkeypatch,
                                                            capsys) -> None:
    early: list[int] = []
    real = runner.start_early
    monkeypatch.setattr(runner, "start_early", lambda: early.append(1) or real())
    robot = workspace / "robot_pkg" / "urdf" / "robot.urdf.xacro"
    code = main(["lint", str(robot), "--no-cache", "--select", "J"])
    assert code in (0, 1)
    assert early == [1]
    assert len(launches) == 1  # the early worker did the expansion: no second start
    assert not runner._EARLY and _gone(launches[0])


def test_an_early_worker_no_expansion_takes_is_killed(workspace, launches) -> None:
    runner.start_early()
    runner.start_early()  # one at a time
    assert len(launches) == 1
    runner.drop_early()
    assert _gone(launches[0]) and not runner._EARLY


def test_the_early_worker_expands_like_a_new_one(workspace, launches) -> None:
    robot = workspace / "robot_pkg" / "urdf" / "robot.urdf.xacro"
    options = ExpandOptions(use_cache=False)
    fresh = expand_file(robot, {"length": "0.3"}, options=options)
    runner.start_early()
    early = expand_file(robot, {"length": "0.3"}, options=options)
    assert len(launches) == 2 and early == fresh


def test_another_process_never_takes_the_early_worker(workspace, launches,
                                                      monkeypatch) -> None:
    runner.start_early()
    monkeypatch.setattr(runner.os, "getpid", lambda: -1)  # as in a forked child
    assert runner._take_early() is None
    monkeypatch.undo()
    taken = runner._take_early()
    assert taken is not None
    runner.kill_group(taken)
