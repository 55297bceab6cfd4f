"""A parsed robot -> a MuJoCo model on a ground plane (built with MjSpec, not MuJoCo's URDF
import); the result is a `robotdesc.sim.scene.Scene`.

Each link becomes a body placed by its parent joint's origin; revolute/continuous joints become
hinges, prismatic joints slides, planar joints two slides and a hinge, fixed joints a weld (no
joint). Limits, damping (N*m*s/rad) and friction (as MuJoCo's frictionloss, N*m) are carried
over. Mimic joints become joint equality constraints (MuJoCo's own URDF import drops them).
The root link gets a free joint (the robot is dropped), unless it is a geometry-less link
called `world`, which the robot is then fixed to. Collision geometry collides with the ground;
self-collision is off by default, as in Gazebo (`selfCollide false`). Inertials are used
exactly as written (`inertiafromgeom` off): the point is to test them.
"""

from __future__ import annotations

import dataclasses
import logging
import math
import re
from typing import Any, Mapping, Sequence

import numpy as np

from robotdesc.errors import SimModelError
from robotdesc.model import tree
from robotdesc.model.elements import (
    Box,
    Capsule,
    Collision,
    Cylinder,
    Joint,
    Link,
    MeshRef,
    Pose,
    Robot,
    Sphere,
)
from robotdesc.sim.backend import import_mujoco
from robotdesc.sim.meshes import MeshAssets
from robotdesc.sim.scene import Scene, SceneOptions, SimJoint, SimMimic
from robotdesc.source import Span
from robotdesc.spatial import (
    perpendicular_axes,
    principal_axes,
    rotation_quaternion,
    rpy_matrix,
    rpy_quaternion,
)

log = logging.getLogger(__name__)

#: Collision bits: robot geoms touch the ground; with self-collision they also touch each other.
_ROBOT_BITS, _GROUND_BITS = 1, 2
#: Joint limits and mimic constraints: stiffer than MuJoCo's default (0.02 s), as in URDF.
_STIFF_SOLREF = (0.005, 1.0)
_MOVING = {"revolute": "hinge", "continuous": "hinge", "prismatic": "slide"}


def build_scene(robot: Robot, meshes: MeshAssets, options: SceneOptions = SceneOptions(),
                actuated: bool = True,
                collision_parts: Mapping[str, Sequence[Any]] | None = None) -> Scene:
    """Build and compile the MuJoCo model of `robot` on a ground plane.

    Args:
        robot: the parsed robot.
        meshes: resolves and converts the robot's meshes.
        options: how the robot is put into the scene.
        actuated: add a position actuator on every non-mimic joint (gains are set by
            `robotdesc.sim.hold`).
        collision_parts: generated collision geometry (link name -> `MeshPart`s and
            `PrimitivePart`s, see `robotdesc.collision`) replacing those links' own.

    Raises:
        SimModelError: the tree cannot be built, or MuJoCo refuses a link (names it).
        SimMeshError: a mesh cannot be resolved or read.
        SimUnavailable: MuJoCo is not installed.
    """
    mujoco = import_mujoco()
    root, children = _tree(robot)
    spec = mujoco.MjSpec()
    spec.modelname = robot.name or "robot"
    spec.compiler.inertiafromgeom = mujoco.mjtInertiaFromGeom.mjINERTIAFROMGEOM_FALSE
    spec.compiler.autolimits = True
    spec.compiler.degree = False  # URDF angles are radians (MuJoCo's default is degrees)
    spec.compiler.balanceinertia = True  # Gazebo accepts slight triangle-inequality misses
    spec.option.timestep = options.timestep
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_EULER
    spec.option.enableflags |= int(mujoco.mjtEnableBit.mjENBL_ENERGY)
    ground = spec.worldbody.add_geom(name="ground", type=mujoco.mjtGeom.mjGEOM_PLANE,
                                     size=[0, 0, 1])
    ground.contype, ground.conaffinity = _GROUND_BITS, _ROBOT_BITS
    ground.friction = [options.friction, 0.005, 0.0001]

    fixed = root.name == "world" and root.inertial is None and not root.collisions
    builder = _Builder(mujoco, spec, robot, meshes, options, collision_parts or {})
    if fixed:
        for joint in children.get(root.name, ()):
            builder.add_link(spec.worldbody, joint, children)
    else:
        body = spec.worldbody.add_body(name=root.name)
        body.add_freejoint(name="__floating_base__")
        builder.fill_body(body, root)
        for joint in children.get(root.name, ()):
            builder.add_link(body, joint, children)
    builder.add_mimic_constraints()
    if actuated:
        builder.add_actuators()
    model = _compile(spec, robot)
    body_links = tuple("" if i == 0 else model.body(i).name for i in range(model.nbody))
    joints = builder.sim_joints(model)
    qpos0 = _start_configuration(mujoco, model, joints, builder.mimics, options, fixed)
    return Scene(model, body_links, joints, tuple(builder.mimics), not fixed, qpos0, robot)


def _tree(robot: Robot) -> tuple[Link, dict[str, list[Joint]]]:
    """The root link and each link's child joints; refuses what is not a tree (the first
    defective joint in document order)."""
    parents = tree.parent_joint_of(robot)
    for joint in robot.joints:
        if robot.link(joint.parent) is None or robot.link(joint.child) is None:
            raise SimModelError(f"joint '{joint.name}' connects a link that does not exist",
                                _where(joint))
        if parents[joint.child] is not joint:
            raise SimModelError(f"link '{joint.child}' has two parent joints", _where(joint),
                                joint.child)
    roots = tree.roots(robot)
    if len(roots) != 1:
        names = ", ".join(link.name for link in roots) or "none (a cycle)"
        raise SimModelError(f"the links do not form one tree (roots: {names})",
                            robot.where.span if robot.where else None)
    return roots[0], tree.children_of(robot)


class _Builder:
    """Adds links, joints, geoms and actuators to a spec (one use per scene)."""

    def __init__(self, mujoco: Any, spec: Any, robot: Robot, meshes: MeshAssets,
                 options: SceneOptions, parts: Mapping[str, Sequence[Any]]) -> None:
        self.mujoco, self.spec, self.robot = mujoco, spec, robot
        self.meshes, self.options, self.parts = meshes, options, parts
        self.mesh_names: dict[str, str] = {}
        self.joint_records: list[tuple[str, str, Joint, str]] = []  # (mj name, kind, joint, link)
        self.mimics: list[SimMimic] = []

    def add_link(self, parent_body: Any, joint: Joint, children: dict[str, list[Joint]]) -> None:
        link = self.robot.link(joint.child)
        if link is None:  # `_tree` refuses such joints first
            raise SimModelError(f"joint '{joint.name}' connects a link that does not exist",
                                _where(joint))
        body = parent_body.add_body(name=link.name, pos=list(joint.origin.xyz),
                                    quat=list(rpy_quaternion(joint.origin.rpy)))
        self._add_joint(body, joint)
        self.fill_body(body, link)
        for child in children.get(link.name, ()):
            self.add_link(body, child, children)

    def fill_body(self, body: Any, link: Link) -> None:
        inertial = link.inertial
        if inertial is not None and inertial.mass is not None and inertial.inertia is not None:
            body.explicitinertial = True
            body.mass = float(inertial.mass)
            body.ipos = list(inertial.origin.xyz)
            rotation = rpy_matrix(inertial.origin.rpy)
            tensor = rotation @ np.asarray(inertial.inertia.matrix(), dtype=float) @ rotation.T
            moments, axes = principal_axes(tensor)
            body.inertia = list(moments)  # zero moments are fine on a welded link
            body.iquat = list(rotation_quaternion(axes.tolist()))
        if link.name in self.parts:
            self._add_parts(body, link, self.parts[link.name])
            return
        shapes = link.visuals if self.options.collision_from_visual else link.collisions
        for index, shape in enumerate(shapes):
            self._add_geom(body, link, shape, index)

    def _add_parts(self, body: Any, link: Link, parts: Sequence[Any]) -> None:
        """Generated collision parts: meshes given as arrays, primitives as geometry."""
        for index, part in enumerate(parts):
            if hasattr(part, "vertices"):
                vertices = np.asarray(part.vertices, dtype=float)
                if is_flat(vertices):  # MuJoCo cannot hull it: a thin box instead
                    self._collide(self._thin_box(body, f"{link.name}/collision{index}",
                                                 vertices))
                    continue
                name = f"generated/{link.name}/{index}"
                mesh = self.spec.add_mesh(name=name)
                mesh.uservert = vertices.ravel().tolist()
                mesh.userface = np.asarray(part.faces, dtype=np.int32).ravel().tolist()
                mesh.inertia = self.mujoco.mjtMeshInertia.mjMESH_INERTIA_CONVEX
                geom = body.add_geom(name=f"{link.name}/collision{index}",
                                     type=self.mujoco.mjtGeom.mjGEOM_MESH, meshname=name)
                self._collide(geom)
            else:
                shape = Collision(None, getattr(part, "origin", Pose()), part.geometry)
                self._add_geom(body, link, shape, index)

    def _add_joint(self, body: Any, joint: Joint) -> None:
        kind = joint.type
        if kind == "fixed":
            return
        if kind == "floating":
            body.add_freejoint(name=joint.name)
            return
        axis = np.asarray(joint.axis if joint.axis is not None else (1.0, 0.0, 0.0), float)
        norm = float(np.linalg.norm(axis))
        if not norm > 0 or not math.isfinite(norm):
            raise SimModelError(f"joint '{joint.name}' has a zero or invalid axis",
                                _where(joint), joint.child)
        axis = axis / norm
        if kind == "planar":
            u, v = (np.array(w) for w in perpendicular_axes(axis.tolist()))
            for suffix, mj_kind, direction in (("x", "slide", u), ("y", "slide", v),
                                               ("yaw", "hinge", axis)):
                self._mj_joint(body, joint, f"{joint.name}__{suffix}", mj_kind, direction,
                               limited=False)
            return
        if kind not in _MOVING:
            raise SimModelError(f"joint '{joint.name}' has type '{kind}', which cannot be "
                                "simulated", _where(joint), joint.child)
        self._mj_joint(body, joint, joint.name, _MOVING[kind], axis,
                       limited=kind != "continuous")
        if joint.mimic is not None and self.robot.joint(joint.mimic.joint) is not None:
            self.mimics.append(SimMimic(joint.name, joint.mimic.joint,
                                        _number(joint.mimic.multiplier, 1.0),
                                        _number(joint.mimic.offset, 0.0), joint.child))

    def _mj_joint(self, body: Any, joint: Joint, name: str, kind: str, axis: np.ndarray,
                  limited: bool) -> None:
        mujoco = self.mujoco
        mj = body.add_joint(name=name, axis=list(axis), solref_limit=list(_STIFF_SOLREF),
                            type=mujoco.mjtJoint.mjJNT_HINGE if kind == "hinge"
                            else mujoco.mjtJoint.mjJNT_SLIDE)
        limit = joint.limit
        if limited and limit is not None and limit.lower is not None \
                and limit.upper is not None and limit.lower < limit.upper:
            mj.limited = mujoco.mjtLimited.mjLIMITED_TRUE
            mj.range = [limit.lower, limit.upper]
        else:
            mj.limited = mujoco.mjtLimited.mjLIMITED_FALSE
        if joint.dynamics is not None:
            _set_damping(mj, max(0.0, _number(joint.dynamics.damping, 0.0)))
            mj.frictionloss = max(0.0, _number(joint.dynamics.friction, 0.0))
        self.joint_records.append((name, kind, joint, joint.child))

    def _add_geom(self, body: Any, link: Link, shape: Any, index: int) -> None:
        mujoco = self.mujoco
        geometry = shape.geometry
        if geometry is None:
            return
        if isinstance(geometry, MeshRef):
            asset = self.meshes.asset(geometry)
            if asset.vertices is not None and is_flat(asset.vertices):
                rotation = rpy_matrix(shape.origin.rpy)
                placed = asset.vertices @ rotation.T + np.asarray(shape.origin.xyz)
                self._collide(self._thin_box(body, f"{link.name}/collision{index}", placed))
                return
        geom = body.add_geom(name=f"{link.name}/collision{index}", pos=list(shape.origin.xyz),
                             quat=list(rpy_quaternion(shape.origin.rpy)))
        if isinstance(geometry, Box):
            geom.type = mujoco.mjtGeom.mjGEOM_BOX
            geom.size = [max(s, 1e-6) / 2 for s in geometry.size]
        elif isinstance(geometry, Cylinder):
            geom.type = mujoco.mjtGeom.mjGEOM_CYLINDER
            geom.size = [geometry.radius, geometry.length / 2, 0]
        elif isinstance(geometry, Sphere):
            geom.type = mujoco.mjtGeom.mjGEOM_SPHERE
            geom.size = [geometry.radius, 0, 0]
        elif isinstance(geometry, Capsule):
            geom.type = mujoco.mjtGeom.mjGEOM_CAPSULE
            geom.size = [geometry.radius, geometry.length / 2, 0]
        elif isinstance(geometry, MeshRef):
            geom.type = mujoco.mjtGeom.mjGEOM_MESH
            geom.meshname = self._mesh(geometry)
        self._collide(geom)

    def _thin_box(self, body: Any, name: str, vertices: np.ndarray) -> Any:
        """A box around flat vertices (in the body frame), at least 1 mm thick."""
        centre = vertices.mean(axis=0)
        _, _, axes = np.linalg.svd(vertices - centre, full_matrices=False)
        if np.linalg.det(axes) < 0:
            axes[2] = -axes[2]
        local = (vertices - centre) @ axes.T
        low, high = local.min(axis=0), local.max(axis=0)
        half = np.maximum((high - low) / 2, 5e-4)
        position = centre + ((high + low) / 2) @ axes
        log.info("%s: flat mesh replaced by a %.3g x %.3g x %.3g m box", name, *(2 * half))
        return body.add_geom(name=name, type=self.mujoco.mjtGeom.mjGEOM_BOX,
                             size=half.tolist(), pos=position.tolist(),
                             quat=list(rotation_quaternion(axes.T.tolist())))

    def _collide(self, geom: Any) -> None:
        geom.contype = _ROBOT_BITS
        geom.conaffinity = _GROUND_BITS | (_ROBOT_BITS if self.options.self_collision else 0)
        geom.friction = [self.options.friction, 0.005, 0.0001]

    def _mesh(self, ref: MeshRef) -> str:
        asset = self.meshes.asset(ref)
        if asset.key in self.mesh_names:
            return self.mesh_names[asset.key]
        mesh = self.spec.add_mesh(name=asset.key)
        if asset.file is not None:
            mesh.file = asset.file
            mesh.scale = list(asset.scale)
        elif asset.vertices is not None and asset.faces is not None:
            mesh.uservert = asset.vertices.ravel().tolist()
            mesh.userface = asset.faces.ravel().tolist()
        mesh.inertia = self.mujoco.mjtMeshInertia.mjMESH_INERTIA_CONVEX
        self.mesh_names[asset.key] = asset.key
        return asset.key

    def add_actuators(self) -> None:
        mujoco = self.mujoco
        followers = {mimic.follower for mimic in self.mimics}
        for name, _kind, joint, _link in self.joint_records:
            if name in followers:
                continue
            actuator = self.spec.add_actuator(name=f"hold/{name}", target=name,
                                              trntype=mujoco.mjtTrn.mjTRN_JOINT)
            actuator.set_to_position(kp=1.0, kv=0.0)  # real gains: robotdesc.sim.hold
            effort = joint.limit.effort if joint.limit is not None else None
            if effort is not None and effort > 0 and math.isfinite(effort):
                actuator.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
                actuator.forcerange = [-effort, effort]

    def sim_joints(self, model: Any) -> tuple[SimJoint, ...]:
        joints = []
        for name, kind, joint, link in self.joint_records:
            mj = model.joint(name)
            lower: float | None = None
            upper: float | None = None
            neutral = 0.0
            if model.jnt_limited[mj.id]:
                low, high = (float(v) for v in model.jnt_range[mj.id])
                lower, upper, neutral = low, high, min(max(0.0, low), high)
            mimic_of = joint.mimic.joint if joint.mimic is not None else None
            effort = joint.limit.effort if joint.limit is not None else None
            joints.append(SimJoint(name, link, kind, int(model.jnt_qposadr[mj.id]),
                                   int(model.jnt_dofadr[mj.id]), lower, upper, neutral,
                                   effort, mimic_of))
        by_name = {j.name: j for j in joints}
        for mimic in self.mimics:  # a follower starts where its constraint puts it
            leader = by_name.get(mimic.leader)
            if leader is not None and mimic.follower in by_name:
                value = mimic.multiplier * leader.neutral + mimic.offset
                follower = by_name[mimic.follower]
                by_name[mimic.follower] = dataclasses.replace(follower, neutral=value)
        return tuple(by_name[j.name] for j in joints)

    def add_mimic_constraints(self) -> None:
        """One joint equality per mimic: follower = offset + multiplier * leader."""
        simulated = {name: kind for name, kind, _joint, _link in self.joint_records}
        kept = []
        for mimic in self.mimics:
            if simulated.get(mimic.leader) is None:
                log.warning("mimic joint '%s' follows '%s', which does not move; ignored",
                            mimic.follower, mimic.leader)
                continue
            equality = self.spec.add_equality(name=f"mimic/{mimic.follower}",
                                              type=self.mujoco.mjtEq.mjEQ_JOINT,
                                              name1=mimic.follower, name2=mimic.leader)
            equality.solref = list(_STIFF_SOLREF)
            data = np.zeros(len(equality.data))
            data[0], data[1] = mimic.offset, mimic.multiplier
            equality.data = data.tolist()
            kept.append(mimic)
        self.mimics = kept


def _compile(spec: Any, robot: Robot) -> Any:
    """Compile, turning MuJoCo's complaints into errors that name the link."""
    try:
        return spec.compile()
    except Exception as error:  # MuJoCo raises ValueError with its compiler message
        message = str(error).strip()
        name = _element_name(message)
        link = name if name and robot.link(name) is not None else ""
        found = robot.link(link) if link else None
        span = found.where.span if found is not None and found.where is not None else None
        first = message.splitlines()[0] if message else type(error).__name__
        raise SimModelError(f"MuJoCo refuses the model: {first}"
                            + (f" (link '{link}')" if link else ""), span, link) from None


def _start_configuration(mujoco: Any, model: Any, joints: tuple[SimJoint, ...],
                         mimics: list[SimMimic], options: SceneOptions,
                         fixed: bool) -> np.ndarray:
    """Joints at neutral; a free robot lifted so its lowest collision point is at the drop height."""
    data = mujoco.MjData(model)
    qpos: np.ndarray = model.qpos0.copy()
    for joint in joints:
        qpos[joint.qpos] = joint.neutral
    data.qpos[:] = qpos
    mujoco.mj_kinematics(model, data)
    if not fixed:
        lowest = lowest_point(model, data)
        if lowest is not None:
            qpos[2] += options.drop_height - lowest
    return qpos


def lowest_point(model: Any, data: Any) -> float | None:
    """The lowest z (m) of the robot's collision geometry (bounding boxes), or None."""
    robot_geoms = [g for g in range(model.ngeom) if model.geom_bodyid[g] != 0]
    if not robot_geoms:
        return None
    corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)],
                       dtype=float)
    lowest = math.inf
    for g in robot_geoms:
        center, half = model.geom_aabb[g, :3], model.geom_aabb[g, 3:]
        points = (center + corners * half) @ data.geom_xmat[g].reshape(3, 3).T + data.geom_xpos[g]
        lowest = min(lowest, float(points[:, 2].min()))
    return lowest


def is_flat(vertices: np.ndarray, tolerance: float = 1e-9) -> bool:
    """Whether points span no volume (coplanar or fewer than 4): MuJoCo cannot hull them."""
    if len(vertices) < 4:
        return True
    spread = np.linalg.svd(vertices - vertices.mean(axis=0), compute_uv=False)
    return bool(spread[-1] <= tolerance * max(float(spread[0]), 1e-300))


def _set_damping(joint: Any, value: float) -> None:
    """Joint damping (N*m*s/rad or N*s/m); newer MuJoCo takes a polynomial (value first)."""
    current = np.asarray(joint.damping, dtype=float)
    if current.ndim == 0:
        joint.damping = value
    else:
        coefficients = np.zeros(current.shape)
        coefficients[0] = value
        joint.damping = coefficients


def _element_name(message: str) -> str | None:
    found = re.search(r"Element name '([^']*)'", message)
    return found.group(1) if found else None


def _number(value: float | None, default: float) -> float:
    return default if value is None or not math.isfinite(value) else float(value)


def _where(joint: Joint) -> Span | None:
    return joint.where.span if joint.where is not None else None
