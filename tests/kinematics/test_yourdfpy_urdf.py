"""`robotdesc.to_yourdfpy`: yourdfpy's model of the expanded description agrees with
robotdesc's own forward kinematics, and its meshes resolve through robotdesc's resolver."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from support import example_robot_data_dir

import robotdesc
from robotdesc.model.tree import SCALAR_TYPES, link_transforms

yourdfpy = pytest.importorskip("yourdfpy", reason="yourdfpy comes with the test extra")

ENGINEER = Path(__file__).resolve().parents[2] / "robots" / "engineer_description" / "urdf" / \
    "engineer.urdf.xacro"
#: example-robot-data robots: an arm (UR5), an arm with a gripper (Panda), a small arm (SO-101).
EXAMPLES = ("ur_description/urdf/ur5_robot.urdf", "panda_description/urdf/panda.urdf",
            "so_arm_description/urdf/so101.urdf")


def _agree(model, robot, seed: int) -> None:
    """Every link pose relative to the root agrees at a random configuration."""
    rng = np.random.default_rng(seed)
    values = {}
    for joint in robot.joints:
        if joint.type in SCALAR_TYPES and joint.mimic is None:
            low, high = (joint.limit.lower, joint.limit.upper) if joint.limit and \
                joint.limit.lower is not None and joint.limit.upper is not None and \
                joint.limit.lower < joint.limit.upper else (-1.0, 1.0)
            values[joint.name] = float(rng.uniform(low, high))
    model.update_cfg({name: values[name] for name in model.actuated_joint_names})
    poses = link_transforms(robot, values)
    root = model.base_link
    assert set(model.link_map) == set(poses)
    worst = max(float(np.abs(model.get_transform(name, root)
                              - np.linalg.inv(poses[root]) @ poses[name]).max()) for name in poses)
    assert worst < 1e-9, worst


def test_the_engineer_in_yourdfpy_has_robotdescs_kinematics() -> None:
    model = robotdesc.to_yourdfpy(ENGINEER, load_meshes=False)
    robot = robotdesc.load(str(ENGINEER))
    assert len(model.link_map) == len(robot.links) == 246
    _agree(model, robot, 0)


def test_xacro_arguments_and_a_lint_result() -> None:
    model = robotdesc.to_yourdfpy(ENGINEER, load_meshes=False, with_gripper="false")
    assert "gripper_base_link" not in model.link_map and len(model.link_map) < 246
    with pytest.raises(robotdesc.errors.UsageError):
        robotdesc.to_yourdfpy(robotdesc.expand(str(ENGINEER)), with_gripper="false")


@pytest.mark.skipif(example_robot_data_dir() is None, reason="example-robot-data is not installed")
@pytest.mark.parametrize("relative", EXAMPLES)
def test_example_robot_data_in_yourdfpy_with_meshes(relative: str) -> None:
    path = example_robot_data_dir() / relative
    model = robotdesc.to_yourdfpy(path)
    robot = robotdesc.load(str(path))
    _agree(model, robot, 1)
    meshed = sum(1 for link in robot.links for v in link.visuals
                 if type(v.geometry).__name__ == "MeshRef")
    assert meshed and len(model.scene.geometry) >= meshed  # every visual mesh was found


@pytest.mark.slow
def test_the_engineer_scene_loads_every_visual_mesh() -> None:
    result = robotdesc.lint(str(ENGINEER), select=["S"])
    model = robotdesc.to_yourdfpy(result)
    meshed = sum(1 for link in result.robot.links for v in link.visuals
                 if type(v.geometry).__name__ == "MeshRef")
    assert len(model.link_map) == len(result.robot.links) == 246
    assert len(model.scene.geometry) >= meshed >= 15  # the body's meshes; wheels are cylinders
