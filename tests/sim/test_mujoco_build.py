"""URDF -> MuJoCo (sim/mujoco_build.py): joints, limits (radians), dynamics, mimic
equalities, meshes, ground."""

from __future__ import annotations

import math

import numpy as np
import pytest

mujoco = pytest.importorskip("mujoco")

from robotdesc.errors import SimModelError  # noqa: E402
from robotdesc.mesh.locate import MeshLocator  # noqa: E402
from robotdesc.model.parse import parse_urdf  # noqa: E402
from robotdesc.sim.meshes import MeshAssets, indexed  # noqa: E402
from robotdesc.sim.mujoco_build import build_scene, lowest_point  # noqa: E402
from robotdesc.sim.scene import SceneOptions  # noqa: E402
from robotdesc.spatial import rotation_quaternion, rpy_matrix, rpy_quaternion  # noqa: E402

from .sim_support import ERD, FIXTURES, load  # noqa: E402


@pytest.fixture(scope="module")
def arm():
    robot, meshes = load(FIXTURES / "slip_arm.urdf")
    return build_scene(robot, meshes)


def test_joints_limits_and_dynamics_are_carried_over(arm) -> None:
    model = arm.model
    elbow = model.joint("elbow")
    assert model.jnt_type[elbow.id] == mujoco.mjtJoint.mjJNT_HINGE
    assert tuple(model.jnt_range[elbow.id]) == (-2.0, 2.0)  # radians, not degrees
    assert model.dof_damping[model.jnt_dofadr[elbow.id]] == pytest.approx(0.05)
    assert model.dof_frictionloss[model.jnt_dofadr[elbow.id]] == pytest.approx(0.01)
    wrist = model.joint("wrist_roll")
    assert not model.jnt_limited[wrist.id]
    finger = model.joint("left_finger")
    assert model.jnt_type[finger.id] == mujoco.mjtJoint.mjJNT_SLIDE
    assert arm.floating and model.jnt_type[0] == mujoco.mjtJoint.mjJNT_FREE


def test_mimic_joint_becomes_an_equality_and_has_no_servo(arm) -> None:
    model = arm.model
    assert model.neq == 1 and model.eq_type[0] == mujoco.mjtEq.mjEQ_JOINT
    assert model.joint(int(model.eq_obj1id[0])).name == "right_finger"
    assert model.joint(int(model.eq_obj2id[0])).name == "left_finger"
    assert tuple(model.eq_data[0, :2]) == (0.0, 1.0)
    servos = {model.actuator(i).name for i in range(model.nu)}
    assert "hold/left_finger" in servos and "hold/right_finger" not in servos
    assert [m.follower for m in arm.mimics] == ["right_finger"]


def test_ground_plane_and_drop_height(arm) -> None:
    model = arm.model
    assert model.geom("ground").type == mujoco.mjtGeom.mjGEOM_PLANE
    data = mujoco.MjData(model)
    data.qpos[:] = arm.qpos0
    mujoco.mj_kinematics(model, data)
    assert lowest_point(model, data) == pytest.approx(0.05, abs=1e-9)


def test_inertia_is_used_as_written(arm) -> None:
    body = arm.model.body("forearm_link")
    assert body.mass[0] == pytest.approx(0.8)
    assert sorted(body.inertia) == pytest.approx(sorted([0.8 * (0.05**2 + 0.25**2) / 12] * 2
                                                        + [0.8 * 2 * 0.05**2 / 12]), rel=1e-4)


def test_rpy_quaternion_matches_rotation_matrix() -> None:
    rpy = (0.3, -0.7, 1.9)
    matrix = np.zeros(9)
    mujoco.mju_quat2Mat(matrix, np.array(rpy_quaternion(rpy)))
    assert np.allclose(matrix.reshape(3, 3), rpy_matrix(rpy))


@pytest.mark.parametrize("rpy", [(0.3, -0.7, 1.9), (3.1, 0.2, -3.0), (0.0, math.pi / 2, 1.0),
                                 (math.pi, 0.0, 0.0), (0.0, 0.0, math.pi), (0.0, 0.0, 0.0)])
def test_rotation_quaternion_is_mujocos(rpy) -> None:
    """spatial.rotation_quaternion replaces mju_mat2Quat in the builder: same numbers."""
    matrix = rpy_matrix(rpy)
    theirs = np.zeros(4)
    mujoco.mju_mat2Quat(theirs, np.ascontiguousarray(matrix).ravel())
    assert np.allclose(rotation_quaternion(matrix.tolist()), theirs, rtol=0, atol=1e-15)


def test_a_massless_moving_link_is_a_model_error_naming_it() -> None:
    text = b"""<robot name="r"><link name="a"><inertial><mass value="1"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
      <link name="ghost"/>
      <joint name="j" type="revolute"><parent link="a"/><child link="ghost"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>"""
    robot = parse_urdf(text, "ghost.urdf")
    with pytest.raises(SimModelError) as caught:
        build_scene(robot, MeshAssets(MeshLocator(robot, lambda name: None)))
    assert caught.value.link == "ghost"
    assert caught.value.span is not None and caught.value.span.line == 3


def test_collada_meshes_are_converted_to_arrays(erd_options) -> None:
    robot, meshes = load(ERD / "robots/ur_description/urdf/ur5_robot.urdf", erd_options)
    scene = build_scene(robot, meshes, SceneOptions(collision_from_visual=True))
    assert scene.model.nmesh > 0
    ref = robot.link("base_link").visuals[0].geometry
    asset = meshes.asset(ref)
    assert ref.filename.endswith(".dae") and asset.file is None
    assert asset.vertices.shape[1] == 3 and asset.faces.max() < len(asset.vertices)


def test_indexed_merges_shared_vertices() -> None:
    soup = np.array([[[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 0], [0, 1, 0]]], float)
    vertices, faces = indexed(soup)
    assert len(vertices) == 4 and faces.shape == (2, 3)
    assert np.allclose(vertices[faces], soup)


def test_quaternions_are_unit() -> None:
    assert math.isclose(float(np.linalg.norm(rpy_quaternion((1.0, 2.0, 3.0)))), 1.0)
