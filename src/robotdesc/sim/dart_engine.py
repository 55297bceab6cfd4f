"""The DART engine behind `EngineScene`: the robot as DART's URDF loader reads the text
`robotdesc.sim.dart_urdf` writes, on a ground box, with ODE's collision detector (meshes
collide triangle by triangle, as in Gazebo).

Defaults as Gazebo's: time step 1 ms (`SceneOptions.timestep` when given), gravity 9.81 m/s^2,
a ground plane (a 100 m box), joints held. Each non-mimic joint is held at its neutral
position by a joint spring and damper (which DART integrates implicitly) tuned like the MuJoCo
servos: natural frequency and damping ratio of `HoldOptions` on the joint's own inertia (the
diagonal of the mass matrix at neutral). Mimic joints follow their leader (DART's mimic
actuator). Drive joints become velocity servos whose force is limited by the effort limit, as
Gazebo's velocity interface.
"""

from __future__ import annotations

import logging
import math
import tempfile
import time
from typing import Any, Mapping, Sequence

import numpy as np

from robotdesc.errors import SimModelError
from robotdesc.model.elements import Robot
from robotdesc.model.tree import roots
from robotdesc.sim.backend import import_dartpy
from robotdesc.sim.dart_urdf import dart_urdf
from robotdesc.sim.engine import EngineScene
from robotdesc.sim.hold import HoldOptions
from robotdesc.sim.meshes import MeshAssets
from robotdesc.sim.native_log import NativeMessage, NativeMessages, native_output_caught
from robotdesc.sim.scene import SceneOptions

log = logging.getLogger(__name__)

_GROUND_SIZE, _GROUND_DEPTH = 100.0, 1.0


def build_scene(robot: Robot, meshes: MeshAssets, options: SceneOptions,
                hold: HoldOptions = HoldOptions(),
                parts: Mapping[str, Sequence[Any]] | None = None) -> "DartScene":
    """The DART scene of `robot`: parsed, placed on the ground, joints held.

    Raises:
        SimModelError: DART cannot load the robot, or a moving link has no mass.
        SimMeshError: a mesh cannot be resolved or read.
    """
    dart = import_dartpy()
    messages = NativeMessages(_link_names(robot))
    with tempfile.TemporaryDirectory(prefix="robotdesc-dart-") as scratch:
        urdf = dart_urdf(robot, meshes, scratch, parts, options.collision_from_visual)
        root = _root_link(robot)
        fixed = root is not None and root.name == "world" and root.inertial is None \
            and not root.collisions
        with native_output_caught(log, messages):  # DART warns of the massless default
            loader = dart.utils.DartLoader()
            loader.setOptions(dart.utils.DartLoaderOptions(
                defaultRootJointType=(dart.utils.DartLoaderRootJointType.FIXED if fixed
                                      else dart.utils.DartLoaderRootJointType.FLOATING),
                defaultInertia=dart.dynamics.Inertia(0.0, [0.0, 0.0, 0.0],
                                                     np.zeros((3, 3)))))
            skeleton = loader.parseSkeletonString(urdf.text,
                                                  dart.common.Uri(f"file://{scratch}/"))
    if skeleton is None:
        raise SimModelError("DART cannot load the robot", robot.where.span if robot.where
                            else None)
    scene = DartScene(dart, robot, skeleton, urdf.geoms, urdf.triangles, options, hold,
                      floating=not fixed, messages=messages)
    scene.mesh_geoms = urdf.mesh_geoms
    return scene


class DartScene(EngineScene):
    """A DART world holding the robot's skeleton and the ground."""

    engine = "dart"

    def __init__(self, dart: Any, robot: Robot, skeleton: Any, geoms: int, triangles: int,
                 options: SceneOptions, hold: HoldOptions, floating: bool,
                 messages: NativeMessages | None = None) -> None:
        self.messages = messages if messages is not None \
            else NativeMessages(_link_names(robot))
        self.mesh_geoms = geoms
        self.dart, self.robot, self.skeleton = dart, robot, skeleton
        self._geoms, self._triangles = geoms, triangles
        self.options, self.hold, self.floating = options, hold, floating
        world = dart.simulation.World()
        world.setTimeStep(options.timestep)
        world.setGravity([0.0, 0.0, -9.81])
        world.setCollisionDetector(dart.collision.OdeCollisionDetector())
        world.addSkeleton(skeleton)
        world.addSkeleton(self._ground())
        skeleton.setSelfCollisionCheck(bool(options.self_collision))
        skeleton.setAdjacentBodyCheck(False)
        self.world = world
        self._set_friction(options.friction)
        self.neutral = self._neutral_positions()
        self.held = self._hold_gains()
        self.start = self._start_positions()
        self.reset()

    # -- EngineScene ---------------------------------------------------------------------

    @property
    def timestep(self) -> float:
        return float(self.world.getTimeStep())

    @property
    def time(self) -> float:
        return float(self.world.getTime())

    @property
    def geoms(self) -> int:
        return self._geoms

    @property
    def triangles(self) -> int:
        return self._triangles

    @property
    def primitives(self) -> int:
        return self._geoms - self.mesh_geoms

    def native_messages(self) -> tuple[NativeMessage, ...]:
        return self.messages.messages()

    def step(self, steps: int = 1) -> None:
        world = self.world
        with native_output_caught(log, self.messages):
            for _ in range(steps):
                world.step(False)  # keep the drive commands (DART clears them)

    def reset(self) -> None:
        with native_output_caught(log, self.messages):
            self._reset()

    def _reset(self) -> None:
        skeleton = self.skeleton
        self.world.reset()
        skeleton.setPositions(self.start)
        skeleton.setVelocities(np.zeros(skeleton.getNumDofs()))
        skeleton.clearExternalForces()
        self._apply_hold()

    def lowest_point(self) -> float:
        lowest = math.inf
        corners = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)],
                           dtype=float)
        for body in self._bodies():
            for index in range(body.getNumShapeNodes()):
                node = body.getShapeNode(index)
                if not node.hasCollisionAspect():
                    continue
                box = node.getShape().getBoundingBox()
                low, high = np.asarray(box.getMin()), np.asarray(box.getMax())
                points = low + corners * (high - low)
                transform = node.getWorldTransform()
                world = points @ np.asarray(transform.rotation()).T \
                    + np.asarray(transform.translation())
                lowest = min(lowest, float(world[:, 2].min()))
        return lowest if math.isfinite(lowest) else float("nan")

    def collision_seconds(self) -> float:
        started = time.perf_counter()
        self.world.checkCollision()
        return time.perf_counter() - started

    def root_pose(self) -> tuple[np.ndarray, np.ndarray]:
        transform = self.skeleton.getBodyNode(0).getWorldTransform()
        return (np.asarray(transform.translation(), dtype=float).copy(),
                np.asarray(transform.rotation(), dtype=float).copy())

    def link_position(self, link: str) -> np.ndarray:
        body = self.skeleton.getBodyNode(link)
        if body is None:
            raise KeyError(f"no link '{link}' in the DART scene")
        position: np.ndarray = np.asarray(body.getWorldTransform().translation(),
                                          dtype=float).copy()
        return position

    def finite(self) -> bool:
        return bool(np.all(np.isfinite(self.skeleton.getPositions()))
                    and np.all(np.isfinite(self.skeleton.getVelocities())))

    def set_drive(self, targets: Mapping[str, float]) -> None:
        with native_output_caught(log, self.messages):
            self._set_drive(targets)

    def _set_drive(self, targets: Mapping[str, float]) -> None:
        servo = self.dart.dynamics.ActuatorType.SERVO
        for name, velocity in targets.items():
            joint = self.skeleton.getJoint(name)
            if joint is None or joint.getNumDofs() != 1 \
                    or joint.getActuatorType() == self.dart.dynamics.ActuatorType.MIMIC:
                raise KeyError(f"joint '{name}' cannot be driven (not a simulated, "
                               "non-mimic joint)")
            joint.setSpringStiffness(0, 0.0)
            joint.setActuatorType(servo)
            effort = self._effort(name)
            joint.setForceLowerLimit(0, -effort)
            joint.setForceUpperLimit(0, effort)
            joint.setCommand(0, float(velocity))

    # -- building ------------------------------------------------------------------------

    def _ground(self) -> Any:
        dart = self.dart
        ground = dart.dynamics.Skeleton("__ground__")
        _, body = ground.createWeldJointAndBodyNodePair()
        node = body.createShapeNode(dart.dynamics.BoxShape(
            [_GROUND_SIZE, _GROUND_SIZE, _GROUND_DEPTH]))
        node.createCollisionAspect()
        node.createDynamicsAspect().setFrictionCoeff(self.options.friction)
        offset = dart.math.Isometry3()
        offset.set_translation([0.0, 0.0, -_GROUND_DEPTH / 2])
        node.setRelativeTransform(offset)
        ground.setMobile(False)
        return ground

    def _bodies(self) -> list[Any]:
        return [self.skeleton.getBodyNode(i) for i in range(self.skeleton.getNumBodyNodes())]

    def _set_friction(self, friction: float) -> None:
        for body in self._bodies():
            for index in range(body.getNumShapeNodes()):
                node = body.getShapeNode(index)
                if node.hasCollisionAspect():
                    aspect = node.getDynamicsAspect() if node.hasDynamicsAspect() \
                        else node.createDynamicsAspect()
                    aspect.setFrictionCoeff(friction)

    def _moving_joints(self) -> list[Any]:
        """The robot's one-degree-of-freedom joints (the root's free joint excluded)."""
        joints = [self.skeleton.getJoint(i) for i in range(self.skeleton.getNumJoints())]
        return [j for j in joints if j.getNumDofs() == 1]

    def _neutral_positions(self) -> dict[str, float]:
        """Each joint's neutral position: 0 clipped into its limits (rad or m)."""
        neutral = {}
        by_name = {joint.name: joint for joint in self.robot.joints}
        for joint in self._moving_joints():
            urdf = by_name.get(joint.getName())
            limit = urdf.limit if urdf is not None else None
            value = 0.0
            if urdf is not None and urdf.type in ("revolute", "prismatic") and limit is not None \
                    and limit.lower is not None and limit.upper is not None \
                    and limit.lower <= limit.upper:
                value = min(max(0.0, limit.lower), limit.upper)
            neutral[joint.getName()] = value
        for joint in self._moving_joints():  # a mimic follower starts where its leader puts it
            urdf = by_name.get(joint.getName())
            if urdf is not None and urdf.mimic is not None and urdf.mimic.joint in neutral:
                multiplier = urdf.mimic.multiplier if urdf.mimic.multiplier is not None else 1.0
                offset = urdf.mimic.offset if urdf.mimic.offset is not None else 0.0
                neutral[joint.getName()] = multiplier * neutral[urdf.mimic.joint] + offset
        return neutral

    def _start_positions(self) -> np.ndarray:
        """Joints at neutral; a free root lifted so its lowest point is at the drop height."""
        skeleton = self.skeleton
        positions = np.zeros(skeleton.getNumDofs())
        for joint in self._moving_joints():
            positions[joint.getIndexInSkeleton(0)] = self.neutral[joint.getName()]
        skeleton.setPositions(positions)
        if self.floating:
            lowest = self.lowest_point()
            if math.isfinite(lowest):
                positions[5] += self.options.drop_height - lowest  # free joint: z translation
        return positions

    def _hold_gains(self) -> dict[str, tuple[float, float]]:
        """(stiffness, damping) per held joint: N*m/rad and N*m*s/rad (N/m, N*s/m)."""
        skeleton = self.skeleton
        positions = np.zeros(skeleton.getNumDofs())
        for joint in self._moving_joints():
            positions[joint.getIndexInSkeleton(0)] = self.neutral[joint.getName()]
        skeleton.setPositions(positions)
        mass = np.asarray(skeleton.getMassMatrix())
        mimic = self.dart.dynamics.ActuatorType.MIMIC
        w, zeta = self.hold.frequency, self.hold.damping_ratio
        gains = {}
        for joint in self._moving_joints():
            if joint.getActuatorType() == mimic:
                continue
            index = joint.getIndexInSkeleton(0)
            inertia = max(float(mass[index, index]), 0.0)
            gains[joint.getName()] = (inertia * w * w, 2.0 * zeta * w * inertia)
        self._damping = {j.getName(): float(j.getDampingCoefficient(0))
                         for j in self._moving_joints()}
        return gains

    def _apply_hold(self) -> None:
        """Springs at neutral (position mode) or damping only (passive); drives cleared."""
        force = self.dart.dynamics.ActuatorType.FORCE
        for joint in self._moving_joints():
            name = joint.getName()
            if name not in self.held:
                continue
            stiffness, damping = self.held[name]
            joint.setActuatorType(force)
            joint.setCommand(0, 0.0)
            joint.setSpringStiffness(0, stiffness if self.hold.mode == "position" else 0.0)
            joint.setRestPosition(0, self.neutral[name])
            joint.setDampingCoefficient(0, max(self._damping[name], damping))

    def _effort(self, name: str) -> float:
        joint = self.robot.joint(name)
        effort = joint.limit.effort if joint is not None and joint.limit is not None else None
        return float(effort) if effort is not None and effort > 0 and math.isfinite(effort) \
            else math.inf


def _link_names(robot: Robot) -> dict[str, str]:
    """Every name DART may print that means a link: links, and joints (their child)."""
    names = {joint.name: joint.child for joint in robot.joints}
    names.update({link.name: link.name for link in robot.links})
    return names


def _root_link(robot: Robot) -> Any:
    heads = roots(robot)
    return heads[0] if len(heads) == 1 else None
