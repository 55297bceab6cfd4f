"""The expansion cache: hits on unchanged inputs, misses when any input changes."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from robotdesc.expansion import ExpandOptions, expand_file, runner

WS = Path(__file__).parent / "fixtures" / "ws"


@pytest.fixture
def workspace(tmp_path):
    shutil.copytree(WS, tmp_path / "ws")
    return tmp_path / "ws" / "src"


@pytest.fixture
def worker_runs(monkeypatch):
    calls = []
    real = runner.run_worker

    def counting(*args, **kwargs):
        calls.append(args[0])
        return real(*args, **kwargs)

    monkeypatch.setattr(runner, "run_worker", counting)
    return calls


def test_second_expansion_is_served_from_the_cache(workspace, worker_runs, tmp_path):
    options = ExpandOptions(cache_dir=str(tmp_path / "cache"))
    robot = workspace / "robot_pkg" / "urdf" / "robot.urdf.xacro"
    first = expand_file(robot, options=options)
    second = expand_file(robot, options=options)
    assert len(worker_runs) == 1
    assert second == first


@pytest.mark.parametrize("change", ["top", "include", "args", "no-cache"])
def test_cache_is_invalidated(change, workspace, worker_runs, tmp_path):
    options = ExpandOptions(cache_dir=str(tmp_path / "cache"))
    robot = workspace / "robot_pkg" / "urdf" / "robot.urdf.xacro"
    expand_file(robot, {"length": "0.3"}, options=options)
    args = {"length": "0.3"}
    if change == "top":
        robot.write_text(robot.read_text().replace("base_link", "root_link"))
    elif change == "include":
        arm = workspace / "arm_pkg" / "urdf" / "arm.xacro"
        arm.write_text(arm.read_text().replace('value="1.0"', 'value="2.0"'))
    elif change == "args":
        args = {"length": "0.4"}
    elif change == "no-cache":
        options = ExpandOptions(use_cache=False)
    result = expand_file(robot, args, options=options)
    assert len(worker_runs) == 2
    expected = {"top": b"root_link", "include": b'value="2.0"', "args": b"0 0 0.4", "no-cache": b"upper"}
    assert expected[change] in result.xml


def test_corrupt_entry_is_a_miss(workspace, worker_runs, tmp_path):
    options = ExpandOptions(cache_dir=str(tmp_path / "cache"))
    robot = workspace / "robot_pkg" / "urdf" / "robot.urdf.xacro"
    expand_file(robot, options=options)
    for entry in (tmp_path / "cache").rglob("*.json"):
        entry.write_text("{not json")
    expand_file(robot, options=options)
    assert len(worker_runs) == 2


def test_a_new_xacro_version_is_a_miss(workspace, worker_runs, tmp_path, monkeypatch):
    from robotdesc.expansion import cache

    options = ExpandOptions(cache_dir=str(tmp_path / "cache"))
    robot = workspace / "robot_pkg" / "urdf" / "robot.urdf.xacro"
    expand_file(robot, options=options)
    real = cache._versions
    monkeypatch.setattr(cache, "_versions", lambda: {**real(), "xacro": "99.0.0"})
    expand_file(robot, options=options)
    assert len(worker_runs) == 2
