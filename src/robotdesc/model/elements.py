"""The URDF model as frozen dataclasses. Every element carries `where`, its provenance.

Units are URDF's: metres, radians, kilograms, kg*m^2, newtons (or N*m), m/s (or rad/s).
Values are kept as written where a rule must judge them: a joint `type` is a plain string
(an invalid type is a finding, not a parse failure); a number that does not parse is None and
is recorded in `Robot.value_issues`.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field

from robotdesc.model.summary import robot_html, robot_repr
from robotdesc.source import Provenance

Vec3 = tuple[float, float, float]


@dataclass(frozen=True)
class Pose:
    """An `<origin>`: translation xyz (m) and roll-pitch-yaw rpy (rad)."""

    xyz: Vec3 = (0.0, 0.0, 0.0)
    rpy: Vec3 = (0.0, 0.0, 0.0)
    where: Provenance | None = None


@dataclass(frozen=True)
class Box:
    """A box of the given full edge lengths (m)."""

    size: Vec3
    where: Provenance | None = None


@dataclass(frozen=True)
class Cylinder:
    """A cylinder along z: radius and length (m)."""

    radius: float
    length: float
    where: Provenance | None = None


@dataclass(frozen=True)
class Sphere:
    """A sphere of the given radius (m)."""

    radius: float
    where: Provenance | None = None


@dataclass(frozen=True)
class Capsule:
    """A capsule along z (a non-standard URDF extension some consumers read): radius, length (m)."""

    radius: float
    length: float
    where: Provenance | None = None


@dataclass(frozen=True)
class MeshRef:
    """A `<mesh filename=... scale=...>` as written (not resolved)."""

    filename: str
    scale: Vec3 = (1.0, 1.0, 1.0)
    where: Provenance | None = None


Geometry = Box | Cylinder | Sphere | Capsule | MeshRef


@dataclass(frozen=True)
class Material:
    """A `<material>`: defined at robot level or inline in a visual.

    Attributes:
        name: material name ("" when anonymous).
        color: rgba in 0..1, if given.
        texture: texture filename, if given.
    """

    name: str
    color: tuple[float, float, float, float] | None = None
    texture: str | None = None
    where: Provenance | None = None


@dataclass(frozen=True)
class Visual:
    name: str | None
    origin: Pose
    geometry: Geometry | None
    material: Material | None = None
    where: Provenance | None = None


@dataclass(frozen=True)
class Collision:
    name: str | None
    origin: Pose
    geometry: Geometry | None
    where: Provenance | None = None


@dataclass(frozen=True)
class Inertia:
    """The six independent entries of the inertia tensor (kg*m^2) about the centre of mass."""

    ixx: float
    ixy: float
    ixz: float
    iyy: float
    iyz: float
    izz: float
    where: Provenance | None = None

    def matrix(self) -> tuple[Vec3, Vec3, Vec3]:
        return ((self.ixx, self.ixy, self.ixz),
                (self.ixy, self.iyy, self.iyz),
                (self.ixz, self.iyz, self.izz))


@dataclass(frozen=True)
class Inertial:
    """Mass (kg), centre-of-mass frame `origin`, and inertia about it (kg*m^2).

    `mass` or `inertia` is None when the element is missing or unparseable.
    """

    origin: Pose
    mass: float | None
    inertia: Inertia | None
    where: Provenance | None = None


@dataclass(frozen=True)
class Link:
    name: str
    inertial: Inertial | None = None
    visuals: tuple[Visual, ...] = ()
    collisions: tuple[Collision, ...] = ()
    where: Provenance | None = None

    def shapes(self) -> Iterator[tuple[str, int, Visual | Collision]]:
        """Every `<visual>`, then every `<collision>`: ("visual" | "collision", its index
        among its kind, the element) (`link:NAME/KIND[INDEX]` names it in findings)."""
        for index, visual in enumerate(self.visuals):
            yield "visual", index, visual
        for index, collision in enumerate(self.collisions):
            yield "collision", index, collision


@dataclass(frozen=True)
class JointLimit:
    """`<limit>`: lower/upper (rad or m), effort (N or N*m), velocity (rad/s or m/s)."""

    lower: float | None = None
    upper: float | None = None
    effort: float | None = None
    velocity: float | None = None
    where: Provenance | None = None


@dataclass(frozen=True)
class Dynamics:
    """`<dynamics>`: damping (N*s/m or N*m*s/rad) and friction (N or N*m)."""

    damping: float | None = None
    friction: float | None = None
    where: Provenance | None = None


@dataclass(frozen=True)
class Mimic:
    """`<mimic>`: this joint = multiplier * joint + offset."""

    joint: str
    multiplier: float | None = 1.0
    offset: float | None = 0.0
    where: Provenance | None = None


@dataclass(frozen=True)
class SafetyController:
    soft_lower_limit: float | None = None
    soft_upper_limit: float | None = None
    k_position: float | None = None
    k_velocity: float | None = None
    where: Provenance | None = None


@dataclass(frozen=True)
class Calibration:
    rising: float | None = None
    falling: float | None = None
    where: Provenance | None = None


@dataclass(frozen=True)
class Joint:
    """A `<joint>`. `parent`/`child` are link names ("" when the element is missing).

    `axis` is None when no `<axis>` is written (URDF's default is 1 0 0).
    """

    name: str
    type: str
    parent: str
    child: str
    origin: Pose = field(default_factory=Pose)
    axis: Vec3 | None = None
    limit: JointLimit | None = None
    dynamics: Dynamics | None = None
    mimic: Mimic | None = None
    safety_controller: SafetyController | None = None
    calibration: Calibration | None = None
    where: Provenance | None = None
    axis_where: Provenance | None = None


@dataclass(frozen=True)
class TransmissionJoint:
    name: str
    hardware_interfaces: tuple[str, ...] = ()
    where: Provenance | None = None


@dataclass(frozen=True)
class Actuator:
    name: str
    hardware_interfaces: tuple[str, ...] = ()
    mechanical_reduction: float | None = None
    where: Provenance | None = None


@dataclass(frozen=True)
class Transmission:
    """A `<transmission>` in either the ROS 1 (`<type>` child) or the old `type=` form."""

    name: str
    type: str
    joints: tuple[TransmissionJoint, ...] = ()
    actuators: tuple[Actuator, ...] = ()
    where: Provenance | None = None


@dataclass(frozen=True)
class GazeboBlock:
    """A `<gazebo>` block: its `reference` (None for robot-wide) and child tag names."""

    reference: str | None
    tags: tuple[str, ...] = ()
    plugins: tuple[str, ...] = ()
    where: Provenance | None = None


@dataclass(frozen=True)
class ValueIssue:
    """An attribute whose value could not be read (a number that is not one, a missing name)."""

    message: str
    where: Provenance | None = None
    element: str = ""


@dataclass(frozen=True)
class Robot:
    """A parsed robot description. Order of links/joints is document order.

    Attributes:
        name: the `<robot name>`.
        source: the file the description came from (the top-level xacro or URDF).
        value_issues: attributes that could not be read; reported by a rule.
    """

    name: str
    links: tuple[Link, ...] = ()
    joints: tuple[Joint, ...] = ()
    materials: tuple[Material, ...] = ()
    transmissions: tuple[Transmission, ...] = ()
    gazebo: tuple[GazeboBlock, ...] = ()
    value_issues: tuple[ValueIssue, ...] = ()
    source: str = ""
    where: Provenance | None = None

    def link(self, name: str) -> Link | None:
        return next((link for link in self.links if link.name == name), None)

    def __repr__(self) -> str:
        """A one-line summary (name, counts, mass, DoF), never the whole model."""
        return robot_repr(self)

    def _repr_html_(self) -> str:
        """A small HTML summary for Jupyter: counts, mass, DoF, the top of the tree."""
        return robot_html(self)

    def joint(self, name: str) -> Joint | None:
        return next((joint for joint in self.joints if joint.name == name), None)

