"""What a robot becomes in a simulator: the scene options, the simulated joints and mimic
constraints, and the compiled MuJoCo scene that maps back to the URDF (built by
`robotdesc.sim.mujoco_build`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from robotdesc.errors import SimOptionError
from robotdesc.model.elements import Robot
from robotdesc.source import Span

if TYPE_CHECKING:
    import numpy as np


@dataclass(frozen=True)
class SceneOptions:
    """How the robot is put into the scene.

    Attributes:
        timestep: integration step (s).
        drop_height: gap between the lowest collision geometry and the ground at start (m).
        self_collision: let the robot's own links collide with each other.
        friction: sliding friction coefficient of every contact (dimensionless).
        collision_from_visual: use the visual geometry as collision geometry.

    Raises:
        SimOptionError: the timestep is not positive or the drop height negative.
    """

    timestep: float = 0.002
    drop_height: float = 0.05
    self_collision: bool = False
    friction: float = 1.0
    collision_from_visual: bool = False

    def __post_init__(self) -> None:
        if not self.timestep > 0:
            raise SimOptionError("timestep", self.timestep,
                                 f"timestep must be positive, got {self.timestep}")
        if not self.drop_height >= 0:
            raise SimOptionError("drop_height", self.drop_height,
                                 f"drop height must be >= 0, got {self.drop_height}")


@dataclass(frozen=True)
class SimJoint:
    """A URDF joint that became MuJoCo degrees of freedom.

    Attributes:
        name: the URDF joint name.
        link: its child link.
        kind: "hinge" or "slide" (planar joints give several).
        qpos: index into MjData.qpos; dof: index into MjData.qvel.
        lower, upper: limits (rad or m), or None when unlimited.
        neutral: the position the joint starts at and is held at (rad or m).
        effort: the effort limit (N*m or N), or None.
        mimic_of: the leader joint when this joint mimics one.
    """

    name: str
    link: str
    kind: str
    qpos: int
    dof: int
    lower: float | None
    upper: float | None
    neutral: float
    effort: float | None = None
    mimic_of: str | None = None


@dataclass(frozen=True)
class SimMimic:
    """A mimic joint as an equality constraint: follower = multiplier * leader + offset."""

    follower: str
    leader: str
    multiplier: float
    offset: float
    link: str


@dataclass(frozen=True, eq=False)
class Scene:
    """A compiled MuJoCo model of the robot and what maps it back to the URDF.

    Attributes:
        model: the `mujoco.MjModel`.
        body_links: the URDF link name of each MuJoCo body ("" for the world body).
        joints: the simulated joints, one entry per degree of freedom of each URDF joint.
        mimics: the mimic constraints.
        floating: the robot has a free joint (it is dropped, not fixed).
        qpos0: the starting configuration (robot above the ground, joints at neutral).
        robot: the robot the scene was built from.
    """

    model: Any
    body_links: tuple[str, ...]
    joints: tuple[SimJoint, ...]
    mimics: tuple[SimMimic, ...]
    floating: bool
    qpos0: np.ndarray
    robot: Robot

    def link_span(self, link: str) -> Span | None:
        """Where the URDF link named `link` is written, when known."""
        found = self.robot.link(link)
        return found.where.span if found is not None and found.where is not None else None
