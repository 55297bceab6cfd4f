"""Real-time factor: simulated seconds per wall-clock second, for the settle scene."""

from __future__ import annotations

import time
from dataclasses import dataclass
from types import ModuleType
from typing import Any

from robotdesc.sim.backend import import_mujoco
from robotdesc.sim.hold import HoldOptions, apply_hold, neutral_controls
from robotdesc.sim.scene import Scene


@dataclass(frozen=True)
class RtfMeasurement:
    """One real-time factor measurement.

    Attributes:
        label: which collision geometry ("as-is", "visual", "generated").
        rtf: simulated seconds per wall second (dimensionless; 1 is real time).
        simulated: simulated time (s).
        wall: wall-clock time spent stepping (s).
        geoms: collision geoms of the robot; mesh_vertices: vertices of its meshes.
    """

    label: str
    rtf: float
    simulated: float
    wall: float
    geoms: int = 0
    mesh_vertices: int = 0


@dataclass(frozen=True)
class RtfComparison:
    """The real-time factor with two collision geometries and their ratio (fast / slow)."""

    baseline: RtfMeasurement
    candidate: RtfMeasurement | None

    @property
    def ratio(self) -> float | None:
        """candidate RTF / baseline RTF (None without a candidate)."""
        if self.candidate is None or self.baseline.rtf <= 0:
            return None
        return self.candidate.rtf / self.baseline.rtf


def measure_rtf(scene: Scene, label: str, seconds: float = 2.0,
                hold: HoldOptions = HoldOptions(), min_wall: float = 0.0) -> RtfMeasurement:
    """Step the settle scene (dropped robot, joints held) and time it; no checks run.

    Args:
        scene: a built scene (its gains are set here).
        label: a name for the collision geometry measured.
        seconds: simulated time per run (s).
        hold: how the joints are held.
        min_wall: repeat the run until at least this much wall time was spent (s), for a
            steadier number on fast models.
    """
    mujoco = import_mujoco()
    model = scene.model
    apply_hold(mujoco, scene, hold)
    controls = neutral_controls(mujoco, scene) if hold.mode == "position" else None
    steps = max(1, round(seconds / model.opt.timestep))
    simulated = wall = 0.0
    while True:
        data = mujoco.MjData(model)
        data.qpos[:] = scene.qpos0
        if controls is not None:
            data.ctrl[:] = controls
        started = time.perf_counter()
        _step(mujoco, model, data, steps)
        wall += time.perf_counter() - started
        simulated += steps * model.opt.timestep
        if wall >= min_wall:
            break
    robot_geoms = [g for g in range(model.ngeom) if model.geom_bodyid[g] != 0]
    mesh_ids = {int(model.geom_dataid[g]) for g in robot_geoms
                if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH}
    vertices = sum(int(model.mesh_vertnum[m]) for m in mesh_ids if m >= 0)
    return RtfMeasurement(label, simulated / wall if wall > 0 else float("inf"), simulated,
                          wall, len(robot_geoms), vertices)


def _step(mujoco: ModuleType, model: Any, data: Any, steps: int) -> None:
    """`steps` MuJoCo steps, in one call when the bindings allow it (less Python overhead).

    `model` and `data` are the `mujoco.MjModel` and `mujoco.MjData` (MuJoCo has no types)."""
    try:
        mujoco.mj_step(model, data, nstep=steps)
    except TypeError:  # older bindings: no nstep
        for _ in range(steps):
            mujoco.mj_step(model, data)
