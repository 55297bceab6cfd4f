"""The R1xx rules on the Engineer: they find the start-up defects D1-D5 of issue 33 in the
packages as they were (ros2_fixtures/engineer_before, a workspace of its own) and nothing in
robots/ as fixed, in every variant its robotdesc.toml lists."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import robotdesc

ROOT = Path(__file__).resolve().parents[2]
BEFORE = Path(__file__).parent / "ros2_fixtures" / "engineer_before" / "src"
GZ_TOP = Path("engineer_gazebo") / "urdf" / "engineer_gz.urdf.xacro"
SMALL = {"main_track_wheels": "4", "flipper_track_wheels": "3"}


def _found(top: Path, args: dict[str, str]) -> list[tuple[str, str, int]]:
    result = robotdesc.lint(str(top), args=args, select=["R1"])
    return sorted((d.code, os.path.relpath(d.where.span.path, top.parents[2]), d.where.span.line)
                  for d in result.diagnostics if d.where is not None)


@pytest.fixture(scope="module")
def before() -> list[tuple[str, str, int]]:
    return _found(BEFORE / GZ_TOP, {})


def test_d1_remaps_on_the_spawners(before):
    assert ("R109", "engineer_control/launch/controllers.launch.py", 42) in before


def test_d2_humble_parameters_in_a_jazzy_package(before):
    removed = [f for f in before if f[0] == "R108"]
    assert {path for _, path, _ in removed} == {
        "engineer_control/config/engineer_ros2_controllers.yaml"}
    assert len(removed) == 14  # use_stamped_vel and six has_*_limits, on both diff drives


def test_d3_ray_sensor_under_gz_sim(before):
    assert ("R105", "engineer_description/urdf/gazebo.xacro", 106) in before


def test_d4_imu_system_in_model_and_world(before):
    assert ("R106", "engineer_gazebo/urdf/ros2_control.xacro", 84) in before


def test_d5_meshes_without_a_gz_resource_path(before):
    assert [f for f in before if f[0] == "R107"] == [
        ("R107", "engineer_description/urdf/chassis_and_tracks.xacro", 56)]


def test_nothing_else_fires_on_the_old_packages(before):
    assert {code for code, _, _ in before} == {"R105", "R106", "R107", "R108", "R109"}


@pytest.mark.parametrize("args", [
    pytest.param({}, marks=pytest.mark.slow),
    pytest.param({"main_track_wheels": "18", "flipper_track_wheels": "31"}, marks=pytest.mark.slow),
    pytest.param({"with_gripper": "false"}, marks=pytest.mark.slow), SMALL],
    ids=["default", "18-31", "no-gripper", "4-3"])
def test_fixed_packages_are_silent(args):
    assert _found(ROOT / "robots" / GZ_TOP, args) == []


def test_fixed_description_is_silent_in_its_classic_default():
    top = ROOT / "robots" / "engineer_description" / "urdf" / "engineer.urdf.xacro"
    assert _found(top, SMALL) == []
