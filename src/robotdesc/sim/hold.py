"""How the joints are held during the settle test: servos tuned to the links' mass and shape.

A real controller is tuned on the real robot, whose inertia follows from its mass and shape;
it does not read the URDF's `<inertia>`. So are these servos: for each joint, robotdesc
estimates the joint-space inertia that the links' masses and collision geometry imply (each
link a solid box filling its geometry's bounding box, about its written centre of mass) and
tunes an explicit PD loop (natural frequency `frequency`, damping ratio `damping_ratio`) to
it. A link whose written inertia is far below what its mass and shape imply (a unit slip)
makes its loop unstable, as it does in Gazebo: the robot "falls apart" on that link.
Links without geometry are judged by their written inertia (nothing to compare with).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from robotdesc.errors import SimOptionError
from robotdesc.sim.scene import Scene

_CORNERS = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)


@dataclass(frozen=True)
class HoldOptions:
    """How joints are held.

    Attributes:
        mode: "position" (servos at the neutral positions) or "passive" (no servos; each
            joint damped with the servo's damping, which MuJoCo integrates implicitly).
        frequency: natural frequency of each servo loop (rad/s).
        damping_ratio: damping ratio of each servo loop (dimensionless).
    """

    mode: Literal["position", "passive"] = "position"
    frequency: float = 30.0
    damping_ratio: float = 0.7

    def __post_init__(self) -> None:
        if self.mode not in ("position", "passive"):
            raise SimOptionError("mode", self.mode, f"hold mode must be 'position' or "
                                 f"'passive', got {self.mode!r}")
        message = "hold frequency must be positive and damping ratio >= 0"
        if not self.frequency > 0:
            raise SimOptionError("frequency", self.frequency, message)
        if not self.damping_ratio >= 0:
            raise SimOptionError("damping_ratio", self.damping_ratio, message)


@dataclass(frozen=True)
class JointInertia:
    """The joint-space inertia of one degree of freedom at the neutral pose.

    Attributes:
        joint: the URDF joint name.
        written: from the written inertials (kg*m^2 or kg).
        shape: from the links' masses and collision geometry (kg*m^2 or kg).
    """

    joint: str
    written: float
    shape: float


def joint_inertias(mujoco: Any, scene: Scene) -> tuple[JointInertia, ...]:
    """Each simulated joint's effective inertia as written and as the links' shapes imply.

    The effective inertia of a joint is what its servo feels at the neutral pose with the
    other joints held still and a free base free to react (a Schur complement of the
    joint-space inertia matrix).
    """
    model = scene.model
    data = mujoco.MjData(model)
    data.qpos[:] = scene.qpos0
    mujoco.mj_forward(model, data)
    written = _effective(mujoco, model, data, scene)
    saved = model.body_inertia.copy(), model.body_iquat.copy()
    try:
        moments, quats = _shape_inertia(mujoco, model, data)
        model.body_inertia[:] = moments
        model.body_iquat[:] = quats
        mujoco.mj_forward(model, data)
        shaped = _effective(mujoco, model, data, scene)
    finally:
        model.body_inertia[:], model.body_iquat[:] = saved
    return tuple(JointInertia(joint.name, float(w), float(s))
                 for joint, w, s in zip(scene.joints, written, shaped))


def _effective(mujoco: Any, model: Any, data: Any, scene: Scene) -> np.ndarray:
    """The effective inertia of each simulated joint's degree of freedom."""
    full = np.zeros((model.nv, model.nv))
    try:
        mujoco.mj_fullM(model, data, full)  # MuJoCo >= 3.4
    except TypeError:
        mujoco.mj_fullM(model, full, data.qM)
    base = list(range(6)) if scene.floating else []
    values = []
    for joint in scene.joints:
        own = full[joint.dof, joint.dof]
        if base:
            coupling = full[joint.dof, base]
            own = own - coupling @ np.linalg.lstsq(full[np.ix_(base, base)], coupling,
                                                    rcond=None)[0]
        values.append(max(float(own), 0.0))
    return np.asarray(values)


def _shape_inertia(mujoco: Any, model: Any, data: Any) -> tuple[np.ndarray, np.ndarray]:
    """Per body: principal moments and inertial-frame quaternions (body frame) of a solid
    box filling the body's geometry bounding box, with the body's written mass."""
    moments, quats = model.body_inertia.copy(), model.body_iquat.copy()
    low = np.full((model.nbody, 3), np.inf)
    high = np.full((model.nbody, 3), -np.inf)
    for g in range(model.ngeom):
        body = int(model.geom_bodyid[g])
        if body == 0:
            continue
        center, half = model.geom_aabb[g, :3], model.geom_aabb[g, 3:]
        points = (center + _CORNERS * half) @ data.geom_xmat[g].reshape(3, 3).T + data.geom_xpos[g]
        low[body] = np.minimum(low[body], points.min(axis=0))
        high[body] = np.maximum(high[body], points.max(axis=0))
    for body in range(1, model.nbody):
        if not np.all(np.isfinite(low[body])):
            continue  # no geometry: keep the written inertia
        d2 = (high[body] - low[body]) ** 2
        world = np.diag([d2[1] + d2[2], d2[0] + d2[2], d2[0] + d2[1]]) * model.body_mass[body] / 12
        rotation = data.xmat[body].reshape(3, 3)
        values, axes = np.linalg.eigh(rotation.T @ world @ rotation)
        if np.linalg.det(axes) < 0:
            axes[:, 2] = -axes[:, 2]
        moments[body] = np.maximum(values, 0.0)
        mujoco.mju_mat2Quat(quats[body], np.ascontiguousarray(axes).ravel())
    return moments, quats


def apply_hold(mujoco: Any, scene: Scene, options: HoldOptions) -> tuple[JointInertia, ...]:
    """Set the servo gains (position mode) or joint damping (passive mode) in `scene.model`.

    Returns:
        The joint inertias the gains were tuned to.
    """
    model = scene.model
    inertias = joint_inertias(mujoco, scene)
    w, zeta = options.frequency, options.damping_ratio
    for joint, inertia in zip(scene.joints, inertias):
        reference = inertia.shape if inertia.shape > 0 else inertia.written
        kp, kv = reference * w * w, 2.0 * zeta * w * reference
        actuator = _actuator_id(mujoco, model, joint.name)
        if options.mode == "passive":
            model.dof_damping[joint.dof] = max(float(model.dof_damping[joint.dof]), kv)
            if actuator is not None:
                model.actuator_gainprm[actuator, 0] = 0.0
                model.actuator_biasprm[actuator, :3] = 0.0
        elif actuator is not None:
            model.actuator_gainprm[actuator, 0] = kp
            model.actuator_biasprm[actuator, :3] = (0.0, -kp, -kv)
    return inertias


def neutral_controls(mujoco: Any, scene: Scene) -> np.ndarray:
    """The control vector holding every actuated joint at its neutral position."""
    controls = np.zeros(scene.model.nu)
    for joint in scene.joints:
        actuator = _actuator_id(mujoco, scene.model, joint.name)
        if actuator is not None:
            controls[actuator] = joint.neutral
    return controls


def _actuator_id(mujoco: Any, model: Any, joint: str) -> int | None:
    found = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, f"hold/{joint}")
    return None if found < 0 else int(found)
