"""The settle test: drop the robot onto the ground, hold its joints, watch what happens.

Four checks, each failing on the first sample that breaks it and naming the link:
- finite: no NaN/infinity in the state (MuJoCo's own bad-state warnings name the degree of
  freedom, hence the link);
- energy: kinetic + potential energy stays below its starting value plus an allowance; it
  grows only when the simulation injects energy (an unstable link);
- joints: joint limits and mimic constraints hold within a tolerance (the robot does not
  "fall apart");
- speed: no link moves or spins faster than plausible.
The settle time is when every link last moved faster than the settle speeds.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from robotdesc.errors import SimOptionError
from robotdesc.sim.backend import import_mujoco
from robotdesc.sim.hold import HoldOptions, JointInertia, apply_hold, neutral_controls
from robotdesc.sim.scene import Scene

log = logging.getLogger(__name__)

CHECKS = ("finite", "energy", "joints", "speed")
#: A joint faster than this fraction of its speed limit is running away.
RUNAWAY_ONSET = 0.1
GRAVITY = 9.81


@dataclass(frozen=True)
class SettleOptions:
    """What the settle test simulates and what it tolerates.

    Attributes:
        seconds: simulated time (s).
        hold: how the joints are held.
        sample_period: time between two checks of the state (s).
        max_link_speed: fastest plausible speed of a prismatic joint or a free base (m/s).
        max_link_spin: fastest plausible speed of a revolute joint or a free base's spin
            (rad/s).
        limit_tolerance: how far a joint may pass its limit (rad for revolute, m x 10 for
            prismatic: 0.1 means 0.1 rad or 0.01 m).
        mimic_tolerance: largest mimic constraint error (rad or m).
        energy_allowance: energy rise allowed, as a fraction of m*g*L (total mass, gravity,
            the robot's size plus the drop height).
        nudge: every held joint starts this far from its neutral position (rad; a tenth of
            it in m for prismatic joints), so that each servo loop has to act; 0 disables.
        settle_speed: a link slower than this is at rest (m/s).
        settle_spin: a link spinning slower than this is at rest (rad/s).
    """

    seconds: float = 2.0
    hold: HoldOptions = field(default_factory=HoldOptions)
    sample_period: float = 0.01
    max_link_speed: float = 50.0
    max_link_spin: float = 500.0
    limit_tolerance: float = 0.1
    mimic_tolerance: float = 0.1
    energy_allowance: float = 0.5
    nudge: float = 0.05
    settle_speed: float = 0.02
    settle_spin: float = 0.2

    def __post_init__(self) -> None:
        if not self.seconds > 0:
            raise SimOptionError("seconds", self.seconds,
                                 f"seconds must be positive, got {self.seconds}")


@dataclass(frozen=True)
class CheckResult:
    """The outcome of one check.

    Attributes:
        name: the check ("finite", "energy", "joints", "speed", or "model").
        passed: whether it held for the whole run.
        message: what went wrong, with the numbers ("" when it passed).
        link: the link to blame ("" when none).
        time: simulated time of the first failure (s), or None.
    """

    name: str
    passed: bool
    message: str = ""
    link: str = ""
    time: float | None = None


@dataclass(frozen=True)
class SettleReport:
    """The settle test's outcome for one robot.

    Attributes:
        robot: the robot's name.
        checks: one result per check, in CHECKS order (or one "model" result when the robot
            could not be simulated).
        settle_time: when every link came to rest (s), or None if it never did.
        simulated: simulated time (s); wall: wall-clock time of the run (s).
        inertias: the joint inertias (written vs implied by shape) the servos were tuned to.
    """

    robot: str
    checks: tuple[CheckResult, ...]
    settle_time: float | None = None
    simulated: float = 0.0
    wall: float = 0.0
    inertias: tuple[JointInertia, ...] = ()

    @property
    def passed(self) -> bool:
        return all(check.passed for check in self.checks)

    @property
    def failures(self) -> tuple[CheckResult, ...]:
        return tuple(check for check in self.checks if not check.passed)

    @property
    def culprit(self) -> str:
        """The link to blame: named by the most causal failed check ("" when it passed)."""
        for name in ("model", "finite", "speed", "energy", "joints"):
            found = self.check(name)
            if found is not None and not found.passed and found.link:
                return found.link
        return ""

    def check(self, name: str) -> CheckResult | None:
        return next((c for c in self.checks if c.name == name), None)


def settle(scene: Scene, options: SettleOptions = SettleOptions()) -> SettleReport:
    """Run the settle test on a built scene (its model's gains are set here).

    Raises:
        SimUnavailable: MuJoCo is not installed.
    """
    mujoco = import_mujoco()
    inertias = apply_hold(mujoco, scene, options.hold)
    watcher = _Watcher(mujoco, scene, options, inertias)
    started = time.perf_counter()
    simulated = watcher.run()
    wall = time.perf_counter() - started
    log.info("%s: %.2f s simulated in %.2f s", scene.robot.name, simulated, wall)
    return SettleReport(scene.robot.name, watcher.results(), watcher.settle_time(), simulated,
                        wall, inertias)


class _Watcher:
    """Steps the simulation and records the first failure of each check."""

    def __init__(self, mujoco: Any, scene: Scene, options: SettleOptions,
                 inertias: tuple[JointInertia, ...]) -> None:
        self.mujoco, self.scene, self.options = mujoco, scene, options
        self.model = scene.model
        self.data = mujoco.MjData(self.model)
        self.data.qpos[:] = nudged(scene, options.nudge)
        self.data.ctrl[:] = neutral_controls(mujoco, scene) if options.hold.mode == "position" \
            else 0.0
        mujoco.mj_forward(self.model, self.data)
        self.failures: dict[str, CheckResult] = {}
        self.last_moving: float | None = 0.0
        self.energy0 = float(np.sum(self.data.energy))
        total_mass = float(np.sum(self.model.body_mass))
        size = _robot_size(self.model, self.data)
        self.allowance = options.energy_allowance * total_mass * GRAVITY * size + 1e-3
        self.previous = self.data.xipos.copy()
        self.inertia_of = {i.joint: i for i in inertias}
        self.runaway = scene.body_links[1] if len(scene.body_links) > 1 else ""
        self.onsets: dict[str, tuple[float, float]] = {}

    def run(self) -> float:
        model, data, mujoco = self.model, self.data, self.mujoco
        steps_per_sample = max(1, round(self.options.sample_period / model.opt.timestep))
        period = steps_per_sample * model.opt.timestep
        samples = max(1, math.ceil(self.options.seconds / period))
        bad_acc = data.warning[int(mujoco.mjtWarning.mjWARN_BADQACC)]
        for _ in range(samples):
            for _ in range(steps_per_sample):
                before = float(data.time)
                mujoco.mj_step(model, data)
                if bad_acc.number > 0:  # MuJoCo has reset the state: report and stop
                    self._fail("finite", "the state became NaN or infinite; the runaway "
                               "joint moves link", self.runaway, before)
                    return before
            if not self._sample(period):
                break
        return float(data.time)

    def _sample(self, period: float) -> bool:
        """Check the state; False when the simulation cannot go on."""
        data, t = self.data, float(self.data.time)
        if not (np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel))):
            self._fail("finite", "the state became NaN or infinite; the runaway joint moves "
                                 "link", self.runaway, t)
            return False
        speeds = np.linalg.norm(data.xipos - self.previous, axis=1) / period
        spins = np.linalg.norm(data.cvel[:, :3], axis=1)
        self.previous = data.xipos.copy()
        speeds[0] = spins[0] = 0.0
        link, value, unit, limit = self._fastest_joint(t)
        if value > limit:
            self._fail("speed", f"joint speed {value:.3g} {unit} (limit {limit:g} {unit}) "
                                "on link", link, t)
        energy = float(np.sum(data.energy))
        if energy - self.energy0 > self.allowance:
            self._fail("energy", f"energy rose by {energy - self.energy0:.3g} J instead of "
                                 f"decaying (allowed {self.allowance:.3g} J); the runaway "
                                 "joint moves link", self.runaway, t)
        self._check_joints(t)
        moving = (speeds > self.options.settle_speed) | (spins > self.options.settle_spin)
        if np.any(moving):
            self.last_moving = t
        return True

    def _fastest_joint(self, t: float) -> tuple[str, float, str, float]:
        """The link moved by the fastest joint relative to its limit: (link, speed, unit,
        limit). A free base counts as a joint of the root link.

        Also follows the runaway: the link whose joint first passed a tenth of its limit
        (an unstable joint flings its children later, so the earliest one is the cause).
        """
        qvel, options = self.data.qvel, self.options
        best, best_ratio = ("", 0.0, "m/s", options.max_link_speed), -1.0
        candidates = [(j.link, abs(float(qvel[j.dof])), j.kind) for j in self.scene.joints]
        if self.scene.floating:
            root = self.scene.body_links[1]
            candidates += [(root, float(np.linalg.norm(qvel[0:3])), "slide"),
                           (root, float(np.linalg.norm(qvel[3:6])), "hinge")]
        measured: dict[str, tuple[float, str, float]] = {}
        for link, speed, kind in candidates:
            limit = options.max_link_spin if kind == "hinge" else options.max_link_speed
            unit = "rad/s" if kind == "hinge" else "m/s"
            if speed / limit > measured.get(link, (0.0, unit, limit))[0] / limit:
                measured[link] = (speed, unit, limit)
            if speed / limit > RUNAWAY_ONSET and link not in self.onsets:
                self.onsets[link] = (t, -speed / limit)
            if speed / limit > best_ratio:
                best_ratio = speed / limit
                best = (link, speed, "rad/s" if kind == "hinge" else "m/s", limit)
        self.runaway = (min(self.onsets, key=self.onsets.__getitem__) if self.onsets
                        else best[0])
        if best[1] > best[3] and self.runaway in measured:
            best = (self.runaway, *measured[self.runaway])
        return best

    def _check_joints(self, t: float) -> None:
        qpos, tolerance = self.data.qpos, self.options.limit_tolerance
        for joint in self.scene.joints:
            if joint.lower is None or joint.upper is None:
                continue
            allowed = tolerance if joint.kind == "hinge" else tolerance / 10
            value = float(qpos[joint.qpos])
            excess = max(joint.lower - value, value - joint.upper)
            if excess > allowed:
                unit = "rad" if joint.kind == "hinge" else "m"
                self._fail("joints", f"joint '{joint.name}' is {excess:.3g} {unit} past its "
                                     f"limit [{joint.lower:g}, {joint.upper:g}]", joint.link, t)
        by_name = {j.name: j for j in self.scene.joints}
        for mimic in self.scene.mimics:
            follower, leader = by_name.get(mimic.follower), by_name.get(mimic.leader)
            if follower is None or leader is None:
                continue
            error = abs(float(qpos[follower.qpos]) - mimic.multiplier * float(qpos[leader.qpos])
                        - mimic.offset)
            if error > self.options.mimic_tolerance:
                self._fail("joints", f"mimic joint '{mimic.follower}' is {error:.3g} off "
                                     f"{mimic.multiplier:g} x '{mimic.leader}'"
                                     + (f" + {mimic.offset:g}" if mimic.offset else ""),
                           mimic.link, t)

    def _link(self, body: int) -> str:
        return self.scene.body_links[body]

    def _fail(self, check: str, message: str, link: str, t: float) -> None:
        if check not in self.failures:
            described = f"{message} '{link}'" if message.endswith("link") else message
            self.failures[check] = CheckResult(check, False, described, link, t)
            log.info("%s check failed at t=%.3f s on %s: %s", check, t, link, described)

    def results(self) -> tuple[CheckResult, ...]:
        return tuple(self.failures.get(name, CheckResult(name, True)) for name in CHECKS)

    def settle_time(self) -> float | None:
        if "finite" in self.failures:
            return None
        final = float(self.data.time)
        if self.last_moving is not None and self.last_moving >= final - 1e-9:
            return None
        return self.last_moving


def nudged(scene: Scene, nudge: float) -> np.ndarray:
    """The start configuration with every non-mimic joint moved `nudge` off neutral (inward)."""
    qpos: np.ndarray = scene.qpos0.copy()
    if nudge == 0:
        return qpos
    followers = {mimic.follower: mimic for mimic in scene.mimics}
    by_name = {joint.name: joint for joint in scene.joints}
    for joint in scene.joints:
        if joint.name in followers:
            continue
        step = nudge if joint.kind == "hinge" else nudge / 10
        target = joint.neutral + step
        if joint.upper is not None and target > joint.upper:
            target = max(joint.neutral - step, joint.lower if joint.lower is not None else -step)
        qpos[joint.qpos] = target
    for follower, mimic in followers.items():
        leader = by_name.get(mimic.leader)
        if leader is not None and follower in by_name:
            qpos[by_name[follower].qpos] = mimic.multiplier * qpos[leader.qpos] + mimic.offset
    return qpos


def _robot_size(model: Any, data: Any) -> float:
    """The robot's largest extent plus its height above the ground (m), at least 0.1 m."""
    points = data.xipos[1:]
    if len(points) == 0:
        return 0.1
    extent = float(np.max(points.max(axis=0) - points.min(axis=0)))
    height = float(max(points[:, 2].max(), 0.0))
    return max(extent + height, 0.1)
