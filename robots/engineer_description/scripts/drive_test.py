#!/usr/bin/env python3
"""Drive the Engineer in MuJoCo as its ROS controllers would, and measure it.

A small stand-in for a drive test until `robotdesc sim` has one: the model is built by
robotdesc's own MuJoCo converter (`robotdesc.sim.convert.build_scene`, the scene `robotdesc
sim` settles), and this script plays the controllers of engineer_control at 1 kHz, as
gazebo_ros_control / gz_ros2_control run them:

- every position-controlled joint (waist, shoulder, elbow, head, flippers, gripper) gets the
  PID of ``config/engineer_control.yaml`` as control_toolbox computes it: p on the error, d on
  the joint velocity, the i term accumulated and clamped to +-i_clamp (no i_clamp: no i term),
  the sum clamped to the joint's effort limit;
- the track wheels are velocity-controlled (VelocityJointInterface; gz_ros2_control sets the
  velocity): an implicit velocity servo (joint damping kv towards the commanded speed),
  limited to the joints' effort;
- the diff drive's kinematics of mobile_base_controller (``config/engineer_tracks.yaml`` of
  engineer_control, with its wheel_separation_multiplier): wheel speed = (v -+ w * separation
  * multiplier / 2) / wheel radius, the same command for every wheel of a side, main and
  flipper tracks alike (the flippers, level at 0, hardly touch the ground).

Measured, each from the robot settled on the ground for 1 s:
  straight   commanded v (m/s), w = 0: the base's mean forward speed over the last second
  spin       v = 0, commanded w (rad/s): the mean yaw rate over the last second
  arc        both
  sag        arm held at full reach (shoulder and elbow straight, forward): the largest
             steady joint error of shoulder and elbow (degrees) after 3 s
  creep      no drive command for 10 s: how far the base moved on the ground (m)

Usage: python scripts/drive_test.py [--case all|straight|spin|arc|sag|creep] [name:=value ...]
Needs: robotdesc[sim] (MuJoCo), PyYAML.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from package_properties import PACKAGE, read_properties

TOP = PACKAGE / "urdf" / "engineer.urdf.xacro"
CONTROL_YAML = PACKAGE.parent / "engineer_control" / "config" / "engineer_control.yaml"
TRACKS_YAML = PACKAGE.parent / "engineer_control" / "config" / "engineer_tracks.yaml"
DT = 0.001             # s: Gazebo's default step, the controllers' update rate
WHEEL_KV = 2.0         # N m s/rad: velocity servo of a wheel (implicit: stable at any wheel inertia)


@dataclass
class Pid:
    """control_toolbox's PID on one joint (effort = p e + i_term - d qdot)."""

    p: float
    i: float
    d: float
    i_clamp: float = 0.0
    integral: float = 0.0

    def effort(self, error: float, velocity: float, dt: float) -> float:
        self.integral += self.i * error * dt
        self.integral = max(-self.i_clamp, min(self.i_clamp, self.integral))
        return self.p * error + self.integral - self.d * velocity


def load_gains(path: Path = CONTROL_YAML) -> dict[str, dict[str, float]]:
    """joint -> pid gains from the position controllers of a controllers YAML (ROS 1 layout
    ``name: {type, joint, pid}`` or ROS 2 layout ``name: {ros__parameters: {joint, gains}}``)."""
    import yaml

    gains: dict[str, dict[str, float]] = {}
    for name, block in yaml.safe_load(path.read_text()).items():
        if not isinstance(block, dict):
            continue
        block = block.get("ros__parameters", block)
        if "joint" in block and "pid" in block:
            gains[block["joint"]] = dict(block["pid"])
    return gains


@dataclass
class Robot:
    mujoco: object
    model: object
    data: object
    scene: object
    pids: dict[int, tuple[object, Pid, float]] = field(default_factory=dict)  # dof -> (joint, pid, effort)
    left: list[int] = field(default_factory=list)     # wheel dofs
    right: list[int] = field(default_factory=list)
    wheel_effort: float = 10.0
    targets: dict[str, float] = field(default_factory=dict)


def expand_with_xacro(args: dict[str, str]) -> str:
    """The URDF by PyPI xacro itself, packages found in robots/ (no ROS needed)."""
    import xacro
    import xacro.substitution_args as substitution

    roots = {p.name: p for p in PACKAGE.parent.iterdir() if (p / "package.xml").is_file()}
    substitution._eval_find = lambda name: str(roots[name])  # noqa: SLF001
    document = xacro.process_file(str(TOP), mappings=dict(args))
    return document.toxml()


def load(args: dict[str, str]):
    """(robot, meshes) as robotdesc parses them; expanded by robotdesc, or by PyPI xacro when
    robotdesc's expansion is unavailable."""
    from robotdesc.model.parse import parse_urdf
    from robotdesc.sim.load import load_sim_input, mesh_assets_for

    try:
        loaded = load_sim_input(str(TOP), args)
        return loaded.robot, loaded.meshes
    except (TypeError, AttributeError, ImportError) as error:  # robotdesc being changed
        print(f"robotdesc expansion failed ({error}); expanding with xacro", file=sys.stderr)
    known = {p.name: str(p) for p in PACKAGE.parent.iterdir() if (p / "package.xml").is_file()}
    robot = parse_urdf(expand_with_xacro(args).encode(), str(TOP))
    return robot, mesh_assets_for(str(TOP), None, known)


def build(args: dict[str, str], gains: dict[str, dict[str, float]]) -> Robot:
    import mujoco

    from robotdesc.sim.convert import SceneOptions, build_scene

    robot_model, meshes = load(args)
    scene = build_scene(robot_model, meshes, SceneOptions(timestep=DT, drop_height=0.005),
                        actuated=False)
    model = scene.model
    model.opt.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    data = mujoco.MjData(model)
    data.qpos[:] = scene.qpos0
    robot = Robot(mujoco, model, data, scene)
    for joint in scene.joints:
        if "_wheel_" in joint.name:
            (robot.left if joint.name.startswith("left_") else robot.right).append(joint.dof)
            robot.wheel_effort = joint.effort or robot.wheel_effort
        elif joint.mimic_of is None and joint.name in gains:
            g = gains[joint.name]
            pid = Pid(float(g.get("p", 0)), float(g.get("i", 0)), float(g.get("d", 0)),
                      abs(float(g.get("i_clamp", 0.0))))
            robot.pids[joint.dof] = (joint, pid, joint.effort or math.inf)
    for dof in robot.left + robot.right:
        model.dof_damping[dof] += WHEEL_KV
    mujoco.mj_forward(model, data)
    return robot


def step(robot: Robot, v: float, w: float, separation: float, radius: float) -> None:
    model, data = robot.model, robot.data
    data.qfrc_applied[:] = 0.0
    for dof, (joint, pid, limit) in robot.pids.items():
        target = robot.targets.get(joint.name, joint.neutral)
        error = target - float(data.qpos[joint.qpos])
        tau = pid.effort(error, float(data.qvel[dof]), DT)
        data.qfrc_applied[dof] = max(-limit, min(limit, tau))
    for dofs, sign in ((robot.left, -1.0), (robot.right, 1.0)):
        speed = (v + sign * w * separation / 2.0) / radius
        for dof in dofs:
            # implicit servo: damping kv pulls towards `speed`; the drive term is limited so
            # that the servo's whole torque stays within the effort limit
            drive = WHEEL_KV * speed
            servo = drive - WHEEL_KV * float(data.qvel[dof])
            if abs(servo) > robot.wheel_effort:
                drive -= servo - math.copysign(robot.wheel_effort, servo)
            data.qfrc_applied[dof] = drive
    robot.mujoco.mj_step(model, data)


def base_pose(robot: Robot) -> tuple[np.ndarray, float]:
    q = robot.data.qpos
    w, x, y, z = q[3:7]
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return np.array(q[0:3]), yaw


def run(robot: Robot, seconds: float, v: float, w: float, props: dict[str, float],
        record: bool = False) -> list[tuple[float, np.ndarray, float]]:
    separation = 2.0 * props["track_offset_y"] * props.get("separation_multiplier", 1.0)
    radius = props["main_wheel_radius"]
    out = []
    for k in range(int(round(seconds / DT))):
        step(robot, v, w, separation, radius)
        if not np.all(np.isfinite(robot.data.qpos)):
            raise FloatingPointError("simulation diverged")
        if record and k % 10 == 0:
            p, yaw = base_pose(robot)
            out.append((robot.data.time, p, yaw))
    return out


def drive(args, gains, props, v, w, seconds=3.0):
    robot = build(args, gains)
    run(robot, 1.0, 0.0, 0.0, props)
    trace = run(robot, seconds, v, w, props, record=True)
    last = [t for t in trace if t[0] >= trace[-1][0] - 1.0]
    (t0, p0, y0), (t1, p1, y1) = last[0], last[-1]
    _, start_yaw = base_pose(robot)
    heading = np.array([math.cos((y0 + y1) / 2), math.sin((y0 + y1) / 2), 0.0])
    dyaw = math.remainder(y1 - y0, 2 * math.pi)
    return {"v": float(np.dot(p1 - p0, heading) / (t1 - t0)), "w": dyaw / (t1 - t0)}


def sag(args, gains, props, seconds=3.0):
    robot = build(args, gains)
    robot.targets = {"shoulder": -0.1, "elbow": 0.0, "head": 0.0}
    run(robot, seconds, 0.0, 0.0, props)
    errors = {}
    for dof, (joint, pid, _) in robot.pids.items():
        if joint.name in ("shoulder", "elbow"):
            errors[joint.name] = math.degrees(robot.targets[joint.name] - robot.data.qpos[joint.qpos])
    return errors


def creep(args, gains, props, seconds=10.0):
    robot = build(args, gains)
    run(robot, 1.0, 0.0, 0.0, props)
    p0, y0 = base_pose(robot)
    run(robot, seconds, 0.0, 0.0, props)
    p1, y1 = base_pose(robot)
    return {"m": float(np.linalg.norm((p1 - p0)[:2])), "yaw_deg": math.degrees(y1 - y0)}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", default="all",
                        choices=["all", "straight", "spin", "arc", "sag", "creep"])
    parser.add_argument("--speed", type=float, default=0.2, help="m/s of each track's belt")
    parser.add_argument("--gains", type=Path, default=CONTROL_YAML)
    parser.add_argument("xacro_args", nargs="*", help="name:=value")
    opts = parser.parse_args(argv)
    args = dict(a.split(":=", 1) for a in opts.xacro_args)
    gains = load_gains(opts.gains)
    props = read_properties()
    import yaml
    tracks = yaml.safe_load(TRACKS_YAML.read_text()) if TRACKS_YAML.is_file() else {}
    props["separation_multiplier"] = float(
        tracks.get("mobile_base_controller", {}).get("wheel_separation_multiplier", 1.0))
    v = opts.speed
    w = 2.0 * v / (2.0 * props["track_offset_y"])  # spin: each belt at v
    results = {}
    cases = ["straight", "spin", "arc", "sag", "creep"] if opts.case == "all" else [opts.case]
    for case in cases:
        if case == "straight":
            r = drive(args, gains, props, v, 0.0)
            results[case] = {"commanded_v": v, **r}
        elif case == "spin":
            r = drive(args, gains, props, 0.0, w)
            results[case] = {"commanded_w": w, **r}
        elif case == "arc":
            r = drive(args, gains, props, v / 2.0, w / 2.0)
            results[case] = {"commanded_v": v / 2.0, "commanded_w": w / 2.0, **r}
        elif case == "sag":
            results[case] = sag(args, gains, props)
        elif case == "creep":
            results[case] = creep(args, gains, props)
        print(json.dumps({case: results[case]}), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
