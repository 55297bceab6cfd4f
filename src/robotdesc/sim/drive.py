"""The drive test: does a wheeled or tracked robot move as it is commanded?

The drive joints come from the package's `diff_drive_controller` configuration (ROS 1
`left_wheel`/`right_wheel`, ROS 2 `left_wheel_names`/`right_wheel_names`, with
`wheel_separation` and `wheel_radius`; one group per controller, as the Engineer's main and
flipper tracks) or from options. A missing radius is taken from the wheel's collision cylinder
or sphere, a missing separation from the wheels' positions. Each wheel turns the way that rolls
the robot forward (+x of the root link), found from its axis.

Three commands, each from rest after the robot has settled: a straight run, a spin in place,
and an arc. For each, the achieved linear (m/s) and angular (rad/s) velocity of the root link is
measured over the last half of the run and compared with the command: a component that is
commanded passes within `tolerance` (a fraction of the command).
"""

from __future__ import annotations

import dataclasses
import glob
import logging
import math
import os
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Iterable, Mapping, Sequence

import numpy as np

from robotdesc.errors import DriveConfigError, SimOptionError
from robotdesc.model.elements import Cylinder, Joint, Robot, Sphere
from robotdesc.model.tree import poses_at
from robotdesc.sim.engine import EngineScene
from robotdesc.source import Span
from robotdesc.spatial import rpy_matrix

log = logging.getLogger(__name__)

#: progress(label, simulated s, total s, wall s so far)
Progress = Callable[[str, float, float, float], None]
_PROGRESS_PERIOD = 2.0


@dataclass(frozen=True)
class DriveGroup:
    """Wheels driven together, as one diff-drive controller drives them.

    Attributes:
        name: the controller's name (or "options").
        left, right: the joint names of the left and right wheels.
        separation: distance between the left and right wheels' mid-planes (m).
        radius: wheel radius (m).
        separation_multiplier, radius_multiplier: the controller's corrections (ROS 2
            diff_drive_controller), applied to the wheel speeds as the controller does.
    """

    name: str
    left: tuple[str, ...]
    right: tuple[str, ...]
    separation: float | None = None
    radius: float | None = None
    separation_multiplier: float = 1.0
    radius_multiplier: float = 1.0


@dataclass(frozen=True)
class DriveCommand:
    """A twist of the root link: linear along its x axis (m/s), angular about z (rad/s)."""

    name: str
    linear: float
    angular: float


@dataclass(frozen=True)
class DriveOptions:
    """How the drive test runs.

    Attributes:
        speed: commanded linear speed of the straight run and the arc (m/s).
        spin: commanded angular speed of the spin (rad/s); None: the wheel speed of the
            straight run, turning in place (2 * speed / separation).
        arc_radius: turning radius of the arc (m); None: the wheel separation.
        seconds: how long each command runs (s); the last half is measured.
        settle: time the robot stands before each command (s).
        tolerance: largest relative error of a commanded component (0.3 = within 30%).
    """

    speed: float = 0.2
    spin: float | None = None
    arc_radius: float | None = None
    seconds: float = 2.0
    settle: float = 0.5
    tolerance: float = 0.3

    def __post_init__(self) -> None:
        message = "drive seconds and tolerance must be positive, settle >= 0"
        if not self.seconds > 0:
            raise SimOptionError("seconds", self.seconds, message)
        if not self.settle >= 0:
            raise SimOptionError("settle", self.settle, message)
        if not self.tolerance > 0:
            raise SimOptionError("tolerance", self.tolerance, message)


@dataclass(frozen=True)
class DriveResult:
    """One command's outcome (velocities in m/s and rad/s, the achieved ones measured)."""

    command: DriveCommand
    linear: float
    angular: float
    checked: tuple[str, ...]
    passed: bool
    finite: bool = True

    def as_dict(self) -> dict[str, Any]:
        return {"command": self.command.name, "commanded_linear": self.command.linear,
                "commanded_angular": self.command.angular, "achieved_linear": self.linear,
                "achieved_angular": self.angular, "checked": list(self.checked),
                "passed": self.passed, "finite": self.finite}


@dataclass(frozen=True)
class DriveReport:
    """The drive test of one robot in one engine."""

    robot: str
    engine: str
    groups: tuple[DriveGroup, ...]
    results: tuple[DriveResult, ...]
    tolerance: float
    wall: float = 0.0

    @property
    def passed(self) -> bool:
        return all(result.passed for result in self.results)

    def as_dict(self) -> dict[str, Any]:
        return {"robot": self.robot, "engine": self.engine, "tolerance": self.tolerance,
                "passed": self.passed, "wall_s": self.wall,
                "groups": [{"name": g.name, "left": list(g.left), "right": list(g.right),
                            "separation_m": g.separation, "radius_m": g.radius,
                            "separation_multiplier": g.separation_multiplier,
                            "radius_multiplier": g.radius_multiplier}
                           for g in self.groups],
                "results": [r.as_dict() for r in self.results]}


# -- finding the drive joints -------------------------------------------------------------

def groups_from_config(source: str, files: Sequence[str] = ()) -> tuple[DriveGroup, ...]:
    """The diff-drive controllers configured for the description `source` (may be none).

    Searches `files` when given; else the YAML files (at most three levels deep) of the
    description's package (the nearest directory up from `source` holding a package.xml) and
    of its sibling packages of the same robot (`engineer_description` -> `engineer_control`,
    `engineer_gazebo`, ...). One group per controller name: the first file in name order wins.
    """
    import yaml

    paths = list(files) if files else sorted(
        path for root in _package_roots(source) for path in set(_yaml_files(root)))
    found: dict[str, DriveGroup] = {}
    for path in paths:
        try:
            with open(path, encoding="utf-8") as handle:
                documents = list(yaml.safe_load_all(handle))
        except (OSError, yaml.YAMLError, UnicodeDecodeError) as error:
            if files:
                raise DriveConfigError(f"cannot read the drive configuration ({error})",
                                       Span(path)) from None
            log.debug("%s: not read (%s)", path, error)
            continue
        for document in documents:
            for group in _groups_in(document, os.path.basename(path)):
                found.setdefault(group.name, group)
    return tuple(found.values())


def _package_roots(source: str) -> list[str]:
    """The description's package directory and its siblings sharing its name's prefix."""
    directory = os.path.dirname(os.path.abspath(source))
    probe = directory
    while not os.path.isfile(os.path.join(probe, "package.xml")):
        parent = os.path.dirname(probe)
        if parent == probe:
            return [directory]
        probe = parent
    name = os.path.basename(probe)
    prefix = name[:-len("_description")] if name.endswith("_description") else None
    roots = [probe]
    if prefix:
        parent = os.path.dirname(probe)
        for sibling in sorted(os.listdir(parent)):
            path = os.path.join(parent, sibling)
            if sibling != name and sibling.startswith(prefix + "_") and os.path.isdir(path):
                roots.append(path)
    return roots


def _yaml_files(root: str) -> Iterable[str]:
    for depth in ("*", "*/*", "*/*/*"):
        for extension in ("yaml", "yml"):
            yield from glob.glob(os.path.join(root, f"{depth}.{extension}"))


def _groups_in(node: Any, where: str, name: str = "") -> list[DriveGroup]:
    """Diff-drive settings anywhere in a YAML tree (a mapping with left and right wheels)."""
    if not isinstance(node, Mapping):
        return []
    left = node.get("left_wheel_names", node.get("left_wheel"))
    right = node.get("right_wheel_names", node.get("right_wheel"))
    if left is not None and right is not None:
        return [DriveGroup(name or where, _names(left), _names(right),
                           _positive(node.get("wheel_separation")),
                           _positive(node.get("wheel_radius")),
                           _positive(node.get("wheel_separation_multiplier")) or 1.0,
                           _positive(node.get("wheel_radius_multiplier")) or 1.0)]
    groups = []
    for key, value in node.items():
        inner = name if key == "ros__parameters" else str(key)
        groups.extend(_groups_in(value, where, inner))
    return groups


def _names(value: Any) -> tuple[str, ...]:
    if isinstance(value, str):
        return (value,)
    return tuple(str(v) for v in value) if isinstance(value, (list, tuple)) else ()


def _positive(value: Any) -> float | None:
    try:
        number = float(value)
    except (TypeError, ValueError):
        return None
    return number if number > 0 and math.isfinite(number) else None


def resolve_groups(robot: Robot, groups: Sequence[DriveGroup]) -> tuple[DriveGroup, ...]:
    """Groups checked against the robot, with missing radius and separation filled in.

    Raises:
        DriveConfigError: no group, a wheel joint the robot does not have, or a size that
            cannot be found.
    """
    if not groups:
        raise DriveConfigError("no drive joints: the package configures no "
                               "diff_drive_controller; give --left-wheels and --right-wheels")
    poses = poses_at(robot)
    resolved = []
    for group in groups:
        if not group.left or not group.right:
            raise DriveConfigError(f"drive group '{group.name}' needs left and right wheels",
                                   group=group.name)
        for name in group.left + group.right:
            joint = robot.joint(name)
            if joint is None or joint.type not in ("continuous", "revolute"):
                raise DriveConfigError(f"drive group '{group.name}': '{name}' is not a "
                                       "revolute or continuous joint of the robot",
                                       group=group.name, joint=name)
        radius = group.radius or _wheel_radius(robot, group.left + group.right)
        separation = group.separation or _separation(robot, poses, group)
        if radius is None or separation is None:
            raise DriveConfigError(f"drive group '{group.name}': give --wheel-radius and "
                                   "--wheel-separation (not found in the model)",
                                   group=group.name)
        resolved.append(dataclasses.replace(group, separation=separation, radius=radius))
    return tuple(resolved)


def wheel_signs(robot: Robot, names: Iterable[str]) -> dict[str, float]:
    """+1 or -1 per wheel joint: the sign of joint velocity that rolls the robot forward.

    Raises:
        DriveConfigError: a wheel's axis is vertical or along the forward direction.
    """
    poses = poses_at(robot)
    signs = {}
    for name in names:
        joint = _wheel(robot, name)
        rotation = poses[joint.parent][:3, :3]
        axis = rotation @ rpy_matrix(joint.origin.rpy) @ np.asarray(
            joint.axis if joint.axis is not None else (1.0, 0.0, 0.0), dtype=float)
        forward = float(np.cross(axis, (0.0, 0.0, 1.0))[0])  # rolling: v = w r (axis x z)
        if abs(forward) < 1e-6 * max(float(np.linalg.norm(axis)), 1e-12):
            raise DriveConfigError(f"wheel joint '{name}' does not roll along the root "
                                   "link's x axis", joint=name)
        signs[name] = 1.0 if forward > 0 else -1.0
    return signs


def _wheel(robot: Robot, name: str) -> Joint:
    """The wheel joint `name`, which `resolve_groups` has found in the robot."""
    joint = robot.joint(name)
    assert joint is not None, f"no wheel joint '{name}': resolve the groups first"
    return joint


def _wheel_radius(robot: Robot, names: Sequence[str]) -> float | None:
    link = robot.link(_wheel(robot, names[0]).child)
    for collision in link.collisions if link is not None else ():
        if isinstance(collision.geometry, (Cylinder, Sphere)):
            return float(collision.geometry.radius)
    return None


def _separation(robot: Robot, poses: Mapping[str, np.ndarray],
                group: DriveGroup) -> float | None:
    """Mean y (m) of the left wheels minus that of the right, in the root link's frame."""
    def mean_y(names: Sequence[str]) -> float:
        return float(np.mean([poses[_wheel(robot, n).child][1, 3] for n in names]))

    separation = mean_y(group.left) - mean_y(group.right)
    return separation if separation > 0 else None


# -- commanding and measuring -------------------------------------------------------------

def commands(groups: Sequence[DriveGroup], options: DriveOptions) -> tuple[DriveCommand, ...]:
    """Straight, spin in place and arc, from the options and the first group's size."""
    separation = groups[0].separation
    assert separation is not None, "resolve the groups first"
    spin = options.spin if options.spin is not None else 2.0 * options.speed / separation
    radius = options.arc_radius if options.arc_radius is not None else separation
    return (DriveCommand("straight", options.speed, 0.0), DriveCommand("spin", 0.0, spin),
            DriveCommand("arc", options.speed, options.speed / radius))


def wheel_targets(groups: Sequence[DriveGroup], signs: Mapping[str, float],
                  command: DriveCommand) -> dict[str, float]:
    """Joint velocity (rad/s) of every wheel for a twist (diff-drive kinematics)."""
    targets = {}
    for group in groups:
        assert group.separation is not None and group.radius is not None, \
            "resolve the groups first"
        half = command.angular * group.separation * group.separation_multiplier / 2.0
        radius = group.radius * group.radius_multiplier
        for names, speed in ((group.left, command.linear - half),
                             (group.right, command.linear + half)):
            for name in names:
                targets[name] = signs[name] * speed / radius
    return targets


def drive_test(scene: EngineScene, robot: Robot, groups: Sequence[DriveGroup],
               options: DriveOptions = DriveOptions(),
               progress: Progress | None = None) -> DriveReport:
    """Run every command from a reset scene and compare the root's velocity with it."""
    signs = wheel_signs(robot, [n for g in groups for n in g.left + g.right])
    started = time.perf_counter()
    results = []
    for command in commands(groups, options):
        results.append(_run(scene, command, wheel_targets(groups, signs, command), options,
                            progress))
        log.info("drive %s: linear %.3g of %.3g m/s, angular %.3g of %.3g rad/s", command.name,
                 results[-1].linear, command.linear, results[-1].angular, command.angular)
    scene.reset()
    return DriveReport(robot.name, scene.engine, tuple(groups), tuple(results),
                       options.tolerance, time.perf_counter() - started)


@dataclass
class _Track:
    """The root's heading, unwrapped, sampled as the run goes."""

    yaw: float = 0.0
    last: float | None = None
    samples: list[tuple[float, np.ndarray, float]] = field(default_factory=list)

    def add(self, t: float, position: np.ndarray, rotation: np.ndarray) -> None:
        heading = math.atan2(rotation[1, 0], rotation[0, 0])
        if self.last is not None:
            self.yaw += (heading - self.last + math.pi) % (2 * math.pi) - math.pi
        self.last = heading
        self.samples.append((t, position[:2].copy(), self.yaw))


def _run(scene: EngineScene, command: DriveCommand, targets: Mapping[str, float],
         options: DriveOptions, progress: Progress | None) -> DriveResult:
    scene.reset()
    chunk = max(1, round(0.01 / scene.timestep))
    wall_start = reported = time.perf_counter()
    total = options.settle + options.seconds

    def advance(until: float, track: _Track | None) -> bool:
        nonlocal reported
        while scene.time < until - scene.timestep / 2:
            scene.step(chunk)
            if not scene.finite():
                return False
            if track is not None:
                track.add(scene.time, *scene.root_pose())
            now = time.perf_counter()
            if progress is not None and now - reported >= _PROGRESS_PERIOD:
                progress(f"drive {command.name}", scene.time, total, now - wall_start)
                reported = now
        return True

    track = _Track()
    ok = advance(options.settle, None)
    if ok:
        scene.set_drive(targets)
        track.add(scene.time, *scene.root_pose())
        ok = advance(total, track)
    if not ok or len(track.samples) < 3:
        return DriveResult(command, float("nan"), float("nan"), (), False, finite=ok)
    t0, p0, yaw0 = _at(track.samples, options.settle + options.seconds / 2)
    t1, p1, yaw1 = track.samples[-1]
    dt = t1 - t0
    heading = _heading_at(track, (yaw0 + yaw1) / 2)  # mid-window heading
    linear = float(np.dot(p1 - p0, heading)) / dt
    angular = (yaw1 - yaw0) / dt
    checked = tuple(name for name, value in (("linear", command.linear),
                                             ("angular", command.angular)) if value != 0)
    passed = all(_within(achieved, wanted, options.tolerance)
                 for name, achieved, wanted in (("linear", linear, command.linear),
                                                ("angular", angular, command.angular))
                 if name in checked)
    return DriveResult(command, linear, angular, checked, passed)


def _at(samples: Sequence[tuple[float, np.ndarray, float]], t: float
        ) -> tuple[float, np.ndarray, float]:
    return next((s for s in samples if s[0] >= t - 1e-9), samples[-1])


def _heading_at(track: _Track, yaw: float) -> np.ndarray:
    """The unit forward direction for an unwrapped yaw, in the world's xy plane."""
    first = track.last - track.yaw if track.last is not None else 0.0  # wrapped heading
    angle = first + yaw
    return np.array([math.cos(angle), math.sin(angle)])


def _within(achieved: float, wanted: float, tolerance: float) -> bool:
    return math.isfinite(achieved) and abs(achieved - wanted) <= tolerance * abs(wanted)
