"""The physics engines of `robotdesc sim`, behind one small interface, in one registry.

An engine builds a scene from a parsed robot (on a ground plane, joints held at neutral, the
root dropped from `drop_height`), steps it, resets it, and reports what the comparisons and the
drive test need: the lowest point of the robot, counts of collision geoms and triangles, the
time of one collision pass, the root's pose, and velocity targets for drive joints.

| engine | extra | collides a mesh as | default time step |
|---|---|---|---|
| mujoco | `robotdesc[sim]` | its convex hull | 2 ms |
| dart | `robotdesc[dart]` | its triangles (ODE's trimesh collider, as Gazebo) | 1 ms (Gazebo's) |

Each backend module is imported only when its engine is asked for.
"""

from __future__ import annotations

import abc
import importlib
from dataclasses import dataclass
from typing import Any, Callable, Mapping, Sequence

import numpy as np

from robotdesc.errors import SimOptionError
from robotdesc.model.elements import Robot
from robotdesc.sim.backend import import_dartpy, import_mujoco
from robotdesc.sim.hold import HoldOptions
from robotdesc.sim.meshes import MeshAssets
from robotdesc.sim.native_log import NativeMessage
from robotdesc.sim.scene import SceneOptions


class EngineScene(abc.ABC):
    """A robot on a ground plane in one engine, ready to step (times in s, lengths in m)."""

    engine: str = ""

    @property
    @abc.abstractmethod
    def timestep(self) -> float:
        """Integration step (s)."""

    @property
    @abc.abstractmethod
    def time(self) -> float:
        """Simulated time since the last reset (s)."""

    @property
    @abc.abstractmethod
    def geoms(self) -> int:
        """Collision shapes of the robot (the ground not counted)."""

    @property
    @abc.abstractmethod
    def triangles(self) -> int:
        """Triangles the engine collides for the robot (MuJoCo: of the meshes' hulls)."""

    @property
    def primitives(self) -> int:
        """Collision shapes that are primitives (boxes, cylinders, spheres, ...)."""
        return 0

    def native_messages(self) -> tuple[NativeMessage, ...]:
        """What the engine's native code printed since the scene was built, counted per
        kind and attributed to links (`robotdesc.sim.native_log`)."""
        return ()

    @abc.abstractmethod
    def step(self, steps: int = 1) -> None:
        """Advance `steps` time steps."""

    @abc.abstractmethod
    def reset(self) -> None:
        """Back to the start: joints at neutral, at rest, dropped from the drop height, t = 0,
        drive targets cleared."""

    @abc.abstractmethod
    def lowest_point(self) -> float:
        """The lowest z of the robot's collision geometry (bounding boxes, m)."""

    @abc.abstractmethod
    def collision_seconds(self) -> float:
        """Wall time of one collision detection pass at the current state (s)."""

    @abc.abstractmethod
    def root_pose(self) -> tuple[np.ndarray, np.ndarray]:
        """The root link's position (m) and rotation matrix (3 x 3) in the world."""

    @abc.abstractmethod
    def link_position(self, link: str) -> np.ndarray:
        """A link's origin in the world (m)."""

    @abc.abstractmethod
    def finite(self) -> bool:
        """Whether the state is free of NaN and infinity."""

    @abc.abstractmethod
    def set_drive(self, targets: Mapping[str, float]) -> None:
        """Drive the named joints at these velocities (rad/s), each limited by its effort
        limit (Gazebo's velocity interface); they stop being held at neutral."""


@dataclass(frozen=True)
class Engine:
    """One registered physics engine.

    Attributes:
        name: the `--engine` value.
        module: the module whose `build_scene(robot, meshes, options, hold, parts)` builds an
            `EngineScene` (imported on first use).
        require: raises `SimUnavailable` (exit 2, with the install hint) when missing.
        default_timestep: the engine's time step unless one is asked for (s).
        collides: how it collides meshes (for reports and docs).
    """

    name: str
    module: str
    require: Callable[[], Any]
    default_timestep: float
    collides: str

    def build(self, robot: Robot, meshes: MeshAssets, options: SceneOptions,
              hold: HoldOptions = HoldOptions(),
              parts: Mapping[str, Sequence[Any]] | None = None) -> EngineScene:
        """Build the scene of `robot` in this engine.

        Raises:
            SimUnavailable: the engine is not installed.
            SimModelError: the robot cannot be simulated (names the link).
            SimMeshError: a mesh cannot be resolved or read.
        """
        self.require()
        scene: EngineScene = importlib.import_module(self.module).build_scene(
            robot, meshes, options, hold, parts)
        return scene


def _require_mujoco() -> Any:
    return import_mujoco()


def _require_dart() -> Any:
    return import_dartpy()


ENGINES: dict[str, Engine] = {
    "mujoco": Engine("mujoco", "robotdesc.sim.mujoco_engine", _require_mujoco, 0.002,
                     "convex hulls"),
    "dart": Engine("dart", "robotdesc.sim.dart_engine", _require_dart, 0.001,
                   "triangles (ODE collision detector)"),
}


def engine(name: str) -> Engine:
    """The registered engine called `name`.

    Raises:
        SimOptionError: no engine has that name.
    """
    if name not in ENGINES:
        raise SimOptionError("engine", name, f"unknown engine {name!r} "
                             f"(known: {', '.join(ENGINES)})")
    return ENGINES[name]
