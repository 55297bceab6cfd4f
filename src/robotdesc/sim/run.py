"""The physics checks end to end for one description file: load, convert, settle, time."""

from __future__ import annotations

import logging
from dataclasses import dataclass, field
from typing import Any, Mapping

from robotdesc.collision.methods import DEFAULT_METHOD
from robotdesc.errors import SimMeshError, SimModelError, SimOptionError
from robotdesc.model.elements import Robot
from robotdesc.sim.meshes import MeshAssets
from robotdesc.sim.mujoco_build import build_scene
from robotdesc.sim.rtf import RtfComparison, measure_rtf
from robotdesc.sim.scene import SceneOptions
from robotdesc.sim.settle import CheckResult, SettleOptions, SettleReport, settle
from robotdesc.sim.variants import COLLISION_MODES, generated_parts, visual_as_collision

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class SimOptions:
    """Everything `robotdesc sim` can change.

    Attributes:
        settle: the settle test's duration, holding and tolerances.
        scene: timestep, drop height, self-collision, friction.
        collision: "as-is", "visual" or "generated".
        generate_method: the `generate_collision` method for "generated".
    """

    settle: SettleOptions = field(default_factory=SettleOptions)
    scene: SceneOptions = field(default_factory=SceneOptions)
    collision: str = "as-is"
    generate_method: str = DEFAULT_METHOD

    def __post_init__(self) -> None:
        if self.collision not in COLLISION_MODES:
            raise SimOptionError("collision", self.collision, f"collision must be one of "
                                 f"{', '.join(COLLISION_MODES)}, got {self.collision!r}")


def settle_robot(robot: Robot, meshes: MeshAssets, options: SimOptions = SimOptions(),
                 package_map: tuple[tuple[str, str], ...] = ()) -> SettleReport:
    """Run the settle test; a robot that cannot be simulated fails the "model" check.

    Raises:
        SimMeshError: a mesh cannot be resolved or read (an input problem, not a result).
        SimUnavailable: MuJoCo is not installed.
    """
    try:
        scene = scene_for(robot, meshes, options, options.collision, package_map)
    except SimModelError as error:
        return SettleReport(robot.name, (CheckResult("model", False, error.message,
                                                     error.link, 0.0),))
    return settle(scene, options.settle)


def scene_for(robot: Robot, meshes: MeshAssets, options: SimOptions, collision: str,
              package_map: tuple[tuple[str, str], ...] = ()) -> Any:
    """The scene with the requested collision geometry."""
    parts: Mapping[str, Any] | None = None
    if collision == "visual":
        robot = visual_as_collision(robot)
    elif collision == "generated":
        parts = generated_parts(robot, method=options.generate_method, package_map=package_map,
                                allow_absolute_paths=meshes.locator.allow_absolute)
    return build_scene(robot, meshes, options.scene, collision_parts=parts)


def compare_rtf(robot: Robot, meshes: MeshAssets, options: SimOptions = SimOptions(),
                baseline: str = "as-is", candidate: str | None = "generated",
                package_map: tuple[tuple[str, str], ...] = (),
                min_wall: float = 0.0) -> RtfComparison:
    """The real-time factor with two collision geometries (candidate may be None)."""
    seconds = options.settle.seconds
    slow = measure_rtf(scene_for(robot, meshes, options, baseline, package_map), baseline,
                       seconds, options.settle.hold, min_wall)
    fast = None
    if candidate is not None:
        fast = measure_rtf(scene_for(robot, meshes, options, candidate, package_map),
                           candidate, seconds, options.settle.hold, min_wall)
    return RtfComparison(slow, fast)


__all__ = ["SimMeshError", "SimOptions", "compare_rtf", "scene_for",
           "settle_robot"]
