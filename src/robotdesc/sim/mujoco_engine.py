"""The MuJoCo engine behind `EngineScene`: the settle scene of `robotdesc.sim.mujoco_build`, its
joints held by the servos of `robotdesc.sim.hold`.

Drive joints switch from their position servo to a velocity servo, force limited by the
effort limit as Gazebo's velocity interface, and the integrator to MuJoCo's
implicit-in-velocity one. Gazebo's servo is a constraint (as stiff as it needs to be); MuJoCo's
is a damper, and one stiff enough to be a constraint on a light wheel rattles against MuJoCo's
soft contacts (measured on the Engineer's 7 mm wheels: stable up to about 0.3 N*m*s/rad,
unstable at 1). Its gain is therefore the torque that carries the wheel's share of the robot's
weight at friction 1 (total mass x g x wheel radius / driven wheels) reached at
`DRIVE_SLIP` of speed error, and at most the effort limit per 1 rad/s.
"""

from __future__ import annotations

import time
from typing import Any, Mapping, Sequence

import numpy as np

from robotdesc.model.elements import Robot
from robotdesc.sim.backend import import_mujoco
from robotdesc.sim.engine import EngineScene
from robotdesc.sim.hold import HoldOptions, apply_hold, neutral_controls
from robotdesc.sim.meshes import MeshAssets
from robotdesc.sim.mujoco_build import build_scene as build_mujoco_scene
from robotdesc.sim.mujoco_build import lowest_point
from robotdesc.sim.scene import Scene, SceneOptions

#: Speed error (rad/s) at which a drive servo pushes the wheel's share of the robot's weight.
DRIVE_SLIP = 0.02
#: The same for a joint without an effort limit, whose servo nothing else bounds: 0.02 made
#: a light wheel's servo stiff enough to rattle (a 1 kg two-wheeler spun at 24 rad/s when
#: told 2.5); at 1 rad/s the servo still carries the weight share and tracks on flat ground.
UNLIMITED_DRIVE_SLIP = 1.0


def build_scene(robot: Robot, meshes: MeshAssets, options: SceneOptions,
                hold: HoldOptions = HoldOptions(),
                parts: Mapping[str, Sequence[Any]] | None = None) -> "MujocoScene":
    """The MuJoCo scene of `robot` (see `robotdesc.sim.mujoco_build.build_scene`)."""
    mujoco = import_mujoco()
    return MujocoScene(mujoco, build_mujoco_scene(robot, meshes, options,
                                                  collision_parts=parts), hold)


class MujocoScene(EngineScene):
    """A MuJoCo model and its data; `scene` keeps the mapping back to the URDF."""

    engine = "mujoco"

    def __init__(self, mujoco: Any, scene: Scene, hold: HoldOptions) -> None:
        self.mujoco, self.scene, self.model = mujoco, scene, scene.model
        self.hold = hold
        self.inertias = apply_hold(mujoco, scene, hold)
        self._held = (self.model.actuator_gainprm.copy(), self.model.actuator_biasprm.copy())
        self._integrator = int(self.model.opt.integrator)
        self.data = mujoco.MjData(self.model)
        self.reset()

    @property
    def timestep(self) -> float:
        return float(self.model.opt.timestep)

    @property
    def time(self) -> float:
        return float(self.data.time)

    @property
    def geoms(self) -> int:
        return sum(1 for g in range(self.model.ngeom) if self.model.geom_bodyid[g] != 0)

    @property
    def primitives(self) -> int:
        return sum(1 for g in range(self.model.ngeom) if self.model.geom_bodyid[g] != 0
                   and self.model.geom_type[g] != self.mujoco.mjtGeom.mjGEOM_MESH)

    @property
    def triangles(self) -> int:
        """Faces of the convex hulls MuJoCo collides (a mesh without a hull: its faces)."""
        model, mujoco = self.model, self.mujoco
        meshes = {int(model.geom_dataid[g]) for g in range(model.ngeom)
                  if model.geom_bodyid[g] != 0
                  and model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH}
        total = 0
        for mesh in meshes:
            address = int(model.mesh_graphadr[mesh])
            total += (int(model.mesh_graph[address + 1]) if address >= 0
                      else int(model.mesh_facenum[mesh]))
        return total

    def step(self, steps: int = 1) -> None:
        try:
            self.mujoco.mj_step(self.model, self.data, nstep=steps)
        except TypeError:  # older bindings: no nstep
            for _ in range(steps):
                self.mujoco.mj_step(self.model, self.data)

    def reset(self) -> None:
        mujoco, model = self.mujoco, self.model
        model.actuator_gainprm[:], model.actuator_biasprm[:] = self._held
        model.opt.integrator = self._integrator
        mujoco.mj_resetData(model, self.data)
        self.data.qpos[:] = self.scene.qpos0
        if self.hold.mode == "position":
            self.data.ctrl[:] = neutral_controls(mujoco, self.scene)
        mujoco.mj_forward(model, self.data)

    def lowest_point(self) -> float:
        self.mujoco.mj_kinematics(self.model, self.data)
        found = lowest_point(self.model, self.data)
        return float("nan") if found is None else found

    def collision_seconds(self) -> float:
        started = time.perf_counter()
        self.mujoco.mj_collision(self.model, self.data)
        return time.perf_counter() - started

    def root_pose(self) -> tuple[np.ndarray, np.ndarray]:
        body = 1 if self.model.nbody > 1 else 0
        return (self.data.xpos[body].copy(), self.data.xmat[body].reshape(3, 3).copy())

    def link_position(self, link: str) -> np.ndarray:
        position: np.ndarray = self.data.xpos[self.model.body(link).id].copy()
        return position

    def finite(self) -> bool:
        return bool(np.all(np.isfinite(self.data.qpos)) and np.all(np.isfinite(self.data.qvel)))

    def set_drive(self, targets: Mapping[str, float]) -> None:
        mujoco, model = self.mujoco, self.model
        model.opt.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
        by_name = {joint.name: joint for joint in self.scene.joints}
        weight = float(np.sum(model.body_mass)) * 9.81 / max(len(targets), 1)  # N per wheel
        for name, velocity in targets.items():
            actuator = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, f"hold/{name}")
            if actuator < 0 or name not in by_name:
                raise KeyError(f"joint '{name}' cannot be driven (not a simulated, "
                               "non-mimic joint)")
            effort = by_name[name].effort
            carry = weight * self._wheel_radius(int(model.actuator_trnid[actuator, 0]))
            if effort is not None and effort > 0 and np.isfinite(effort):
                gain = min(carry / DRIVE_SLIP, effort)
            else:  # no effort limit (continuous joints often have none): a gentler servo
                gain = carry / UNLIMITED_DRIVE_SLIP
            model.actuator_gainprm[actuator, 0] = gain
            model.actuator_biasprm[actuator, :3] = (0.0, 0.0, -gain)
            self.data.ctrl[actuator] = velocity

    def _wheel_radius(self, joint: int) -> float:
        """The radius of the wheel a joint turns (m): its cylinder's or sphere's, else its
        geometry's bounding radius, 0.05 m without any."""
        model, kinds = self.model, self.mujoco.mjtGeom
        body = int(model.jnt_bodyid[joint])
        round_kinds = (int(kinds.mjGEOM_CYLINDER), int(kinds.mjGEOM_SPHERE))
        radii = [float(model.geom_size[g, 0]) if int(model.geom_type[g]) in round_kinds
                 else float(model.geom_rbound[g])
            for g in range(model.ngeom) if model.geom_bodyid[g] == body]
        return max(radii) if radii else 0.05
