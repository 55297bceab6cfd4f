"""Mesh rules (M1xx): every `<mesh>` must lead to a readable, sound mesh file of the right
size, and collision geometry must be fit for a physics engine.

All but M115 need meshes (`ctx.meshes`, a `robotdesc.mesh.context.MeshContext`); each
finding sits at the `<mesh>` element's line. References that are absolute, `file://` or of
another scheme are reported by the path rules (P1xx) and not read here unless the config
allows absolute paths.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING

from robotdesc.diagnostics import Finding, Severity, ValueChange
from robotdesc.inertia.links import is_dynamics_model
from robotdesc.mesh.records import MassMethod, MeshSummary
from robotdesc.mesh.resolve import local_path
from robotdesc.mesh.scale_check import looks_like_millimetres, robot_size
from robotdesc.model.elements import Joint, Link, MeshRef, Robot
from robotdesc.model.tree import parent_joint_of
from robotdesc.rules.paths import made_by_find
from robotdesc.rules.registry import RuleContext, rule

if TYPE_CHECKING:
    from robotdesc.mesh.context import MeshLookup

#: One `<mesh>` as the rules see it: link, "visual"/"collision", index, reference, lookup.
MeshEntry = tuple[Link, str, int, MeshRef, "MeshLookup"]
#: A health check: a problem's message for a mesh summary, or None.
HealthCheck = Callable[[MeshSummary], "str | None"]

FAMILY = "meshes"
NEEDS = ("meshes",)
#: A link lighter than this (kg) is a placeholder frame, not a body (M115 skips it).
DUMMY_MASS = 1e-3
#: M111 calls a mesh inverted only when |signed volume| is at least this share of its
#: bounding box's volume.
INVERTED_VOLUME_FRACTION = 0.01
#: A mesh no wider than this (m, its bounding box's diagonal) on a link attached by a fixed
#: joint is a small fixed part (a camera, a sonar, a cover): Gazebo lumps it into its parent
#: and no result depends on its mesh's hygiene or triangle count.
SMALL_PART_SIZE = 0.2


def _element(link: Link, kind: str, index: int) -> str:
    return f"link:{link.name}/{kind}[{index}]"


def _lookups(ctx: RuleContext, physical_only: bool = False) -> Iterator[MeshEntry]:
    """(link, kind, index, reference, lookup) per `<mesh>`; `physical_only`: only meshes
    whose volume robotdesc uses (see `_volume_used`)."""
    if ctx.meshes is None:
        return
    source = ctx.meshes.settings.inertia_source
    for link, kind, index, _shape, ref in ctx.meshes.meshes():
        if physical_only and not _volume_used(link, kind, source):
            continue
        yield link, kind, index, ref, ctx.meshes.lookup(ref)


def _volume_used(link: Link, kind: str, source: str) -> bool:
    """Collision meshes (engines collide with their volume), and visual meshes of a link
    whose declared mass properties are judged from them: the link has an `<inertial>` with
    a positive mass, and visual geometry is the configured source or the link has no
    collision geometry."""
    if kind == "collision":
        return True
    inertial = link.inertial
    if inertial is None or inertial.mass is None or not inertial.mass > 0:
        return False
    return source == "visual" or not link.collisions


def _resolve_problems(ctx: RuleContext, kinds: set[str]) -> Iterator[Finding]:
    for link, kind, index, ref, found in _lookups(ctx):
        problem = found.resolution.problem
        if problem is not None and problem.kind.value in kinds:
            yield Finding(problem.message, ref.where, _element(link, kind, index))


def _mesh_errors(ctx: RuleContext, kinds: set[str] | None, exclude: frozenset[str] = frozenset()
                 ) -> Iterator[Finding]:
    for link, kind, index, ref, found in _lookups(ctx):
        error = found.error
        if error is None or error.kind.value in exclude:
            continue
        if kinds is None or error.kind.value in kinds:
            yield Finding(f"'{ref.filename}' ({error.kind.value}): {error.detail}", ref.where,
                          _element(link, kind, index))


@rule("M101", "mesh-file-missing", family=FAMILY, severity=Severity.ERROR, needs=NEEDS)
def mesh_file_missing(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a `<mesh>` whose file does not exist (or whose `package://` names no file).
    A `file://` URI or an absolute path that the expansion made with `$(find pkg)` (the
    source is portable, so P101/P102 say nothing) is checked too, even when the config does
    not allow such paths: zed-ros2-wrapper's `file://$(find zed_msgs)/meshes/...` names
    meshes its package does not hold. One written out in the source is P101's or P102's.

    Why is this bad?
    Viewers show nothing, simulators refuse the model or drop the collision, and nothing
    can be computed from the mesh.

    Example
    ```xml
    <link name="arm">
      <visual><geometry><mesh filename="package://arm/meshes/upperarm.stl"/></geometry></visual>
    </link>
    ```

    Use instead (the file that exists):
    ```xml
    <link name="arm">
      <visual><geometry><mesh filename="package://arm/meshes/upper_arm.stl"/></geometry></visual>
    </link>
    ```
    """
    yield from _resolve_problems(ctx, {"missing", "empty"})
    for link, kind, index, ref, found in _lookups(ctx):
        problem = found.resolution.problem
        if problem is None or problem.kind.value != "absolute-not-allowed":
            continue
        path = local_path(ref.filename)
        if path is not None and made_by_find(ref.filename, ctx) and not os.path.exists(path):
            yield Finding(f"mesh file '{path}' ({ref.filename}) does not exist", ref.where,
                          _element(link, kind, index))


@rule("M102", "mesh-name-case-mismatch", family=FAMILY, severity=Severity.ERROR, needs=NEEDS)
def mesh_name_case_mismatch(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a mesh filename that matches an existing file only when case is ignored.

    Why is this bad?
    It works on Windows and macOS, whose file systems ignore case, and fails on Linux,
    where ROS runs: `cronstain.dae` is not `Cronstain.dae`.

    Example
    ```xml
    <link name="arm">
      <visual><geometry><mesh filename="package://arm/meshes/cronstain.dae"/></geometry></visual>
    </link>
    ```

    Use instead:
    ```xml
    <link name="arm">
      <visual><geometry><mesh filename="package://arm/meshes/Cronstain.dae"/></geometry></visual>
    </link>
    ```
    """
    for link, kind, index, ref, found in _lookups(ctx):
        problem = found.resolution.problem
        if problem is None or problem.kind.value != "case-mismatch":
            continue
        element = _element(link, kind, index)
        fixed = _case_fixed(ref.filename, problem.candidate)
        yield Finding(problem.message, ref.where, element,
                      changes=() if fixed is None else
                      (ValueChange(f"{element}/geometry/mesh", "filename", fixed),),
                      unfixable="the file with the right case was not found" if fixed is None
                      else "")


def _case_fixed(filename: str, candidate: str | None) -> str | None:
    """M102's fix: `filename` with its trailing parts spelt as the file on disk
    `candidate` (None: no file to follow)."""
    if not candidate:
        return None
    parts = filename.split("/")
    actual = os.path.normpath(candidate).split(os.sep)
    fixed = list(parts)
    for offset in range(1, min(len(parts), len(actual)) + 1):
        if parts[-offset].lower() != actual[-offset].lower():
            break
        fixed[-offset] = actual[-offset]
    return "/".join(fixed)


@rule("M103", "unknown-mesh-package", family=FAMILY, severity=Severity.ERROR, needs=NEEDS)
def unknown_mesh_package(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a `package://NAME/...` mesh whose package no resolver knows.

    robotdesc never falls back to another package that happens to hold the same relative
    path: that would check a file the robot's users will not get.

    Why is this bad?
    Every consumer resolves the package by name; a misspelt or undeclared package leaves
    the mesh missing on every machine but the author's.

    Example
    ```xml
    <link name="arm">
      <visual><geometry><mesh filename="package://arm_descripton/meshes/arm.stl"/></geometry></visual>
    </link>
    ```

    Use instead:
    ```xml
    <link name="arm">
      <visual><geometry><mesh filename="package://arm_description/meshes/arm.stl"/></geometry></visual>
    </link>
    ```
    """
    yield from _resolve_problems(ctx, {"unknown-package"})


@rule("M104", "mesh-path-escapes-package", family=FAMILY, severity=Severity.ERROR, needs=NEEDS)
def mesh_path_escapes_package(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a mesh path that leaves its package root, by `..` or through a symlink.

    Why is this bad?
    The file is not part of the package: an installed or released package does not carry
    it, and a description should not read files outside what it ships.

    Example
    ```xml
    <link name="arm">
      <visual><geometry><mesh filename="package://arm/../../secret/arm.stl"/></geometry></visual>
    </link>
    ```

    Use instead:
    ```xml
    <link name="arm">
      <visual><geometry><mesh filename="package://arm/meshes/arm.stl"/></geometry></visual>
    </link>
    ```
    """
    yield from _resolve_problems(ctx, {"escapes-root"})


@rule("M105", "mesh-not-a-regular-file", family=FAMILY, severity=Severity.ERROR, needs=NEEDS)
def mesh_not_a_regular_file(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a mesh path that is a directory, a FIFO, a device or a socket.

    Why is this bad?
    It is not a mesh; reading a FIFO or a device can block a loader forever.

    Example
    ```xml
    <link name="arm">
      <visual><geometry><mesh filename="package://arm/meshes"/></geometry></visual>
    </link>
    ```

    Use instead:
    ```xml
    <link name="arm">
      <visual><geometry><mesh filename="package://arm/meshes/arm.stl"/></geometry></visual>
    </link>
    ```
    """
    yield from _resolve_problems(ctx, {"not-regular-file"})


@rule("M106", "mesh-is-lfs-pointer", family=FAMILY, severity=Severity.ERROR, needs=NEEDS)
def mesh_is_lfs_pointer(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a mesh file that is a Git LFS pointer, not a mesh.

    Why is this bad?
    The repository stores its meshes with Git LFS and this checkout never fetched them
    (`git lfs pull`, or `lfs: true` in CI): every consumer sees a 130-byte text file.

    Example
    ```xml
    <link name="arm">
      <!-- meshes/arm.stl holds "version https://git-lfs.github.com/spec/v1 ..." -->
      <visual><geometry><mesh filename="package://arm/meshes/arm.stl"/></geometry></visual>
    </link>
    ```

    Use instead (after `git lfs pull`):
    ```xml
    <link name="arm">
      <visual><geometry><mesh filename="package://arm/meshes/arm.stl"/></geometry></visual>
    </link>
    ```
    """
    yield from _mesh_errors(ctx, {"lfs-pointer"})


@rule("M107", "malformed-mesh-file", family=FAMILY, severity=Severity.ERROR, needs=NEEDS)
def malformed_mesh_file(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a mesh file whose geometry cannot be read: truncated, a binary STL whose
    header claims more triangles than the file holds, NaN or infinite coordinates, face
    indices out of range, no triangles, an unsupported format, or over the size limits.

    The message names the cause (`truncated`, `non-finite`, `bad-index`, `too-large`, ...).
    A COLLADA file whose geometry reads but whose material or texture references are
    broken is not malformed: that is M116's milder finding.

    Why is this bad?
    Consumers crash, hang allocating for a bogus header, or silently load garbage (NaN
    vertices poison every computation that touches them).

    Example
    ```xml
    <link name="arm">
      <!-- arm.stl was cut short by an interrupted copy -->
      <collision><geometry><mesh filename="package://arm/meshes/arm.stl"/></geometry></collision>
    </link>
    ```

    Use instead (a complete export):
    ```xml
    <link name="arm">
      <collision><geometry><mesh filename="package://arm/meshes/arm_fixed.stl"/></geometry></collision>
    </link>
    ```
    """
    yield from _mesh_errors(ctx, None, exclude=frozenset({"lfs-pointer"}))


@rule("M116", "mesh-broken-material-reference", family=FAMILY, severity=Severity.WARNING,
      needs=NEEDS)
def mesh_broken_material_reference(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a COLLADA mesh whose geometry reads but whose materials, effects or texture
    images do not resolve: an `<instance_material>` naming no `<material>`, an effect
    sampling a surface that is not defined, an `<image>` whose file does not exist.

    References to the exporter's cameras and lights are not reported: no URDF consumer
    draws them (Fetch's meshes name a camera and a lamp their file lacks).

    Each file is reported once per robot, at its first `<mesh>`.

    Why is this bad?
    RViz (assimp) and Gazebo draw the geometry with a default grey material or without its
    texture, and loaders that build the materials first (pycollada, some exporters'
    re-importers) drop the node that uses the broken material, geometry and all.

    Example
    ```xml
    <link name="foot">
      <!-- foot.dae: <instance_material target="#carbon-material"/>, and no such material -->
      <visual><geometry><mesh filename="package://leg/meshes/foot.dae"/></geometry></visual>
    </link>
    ```

    Use instead (the material defined, or the binding removed):
    ```xml
    <link name="foot">
      <!-- foot.dae: <material id="carbon-material"> defined in <library_materials> -->
      <visual><geometry><mesh filename="package://leg/meshes/foot.dae"/></geometry></visual>
    </link>
    ```
    """
    seen: set[str] = set()
    for link, kind, index, ref, found in _lookups(ctx):
        summary = found.summary
        path = found.resolution.path
        if summary is None or path is None or path in seen:
            continue
        problems = tuple(p for p in summary.broken_references if not _scene_only(p))
        if not problems:
            continue
        seen.add(path)
        listed = "; ".join(problems[:3]) + (f"; and {len(problems) - 3} more"
                                            if len(problems) > 3 else "")
        yield Finding(f"'{ref.filename}' has broken material or texture references "
                      f"({listed}); its geometry ({summary.health.triangles} triangles) is "
                      "read without them", ref.where, _element(link, kind, index))


def _scene_only(problem: str) -> bool:
    """A broken reference to a camera or a light of the exporter's scene (Fetch's DAE files:
    `Camera #Camera-camera not found in library`): no consumer of a URDF mesh draws those,
    so nothing is lost."""
    return problem.startswith(("Camera ", "Light "))


@rule("M108", "mesh-in-millimetres", family=FAMILY, severity=Severity.WARNING, needs=NEEDS)
def mesh_in_millimetres(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a mesh about a thousand times larger than the robot it belongs to: one
    exported in millimetres and used without `scale="0.001 0.001 0.001"`.

    The robot's size is taken from its joint positions (and from its other meshes); the
    mesh is reported when it is far larger and a thousandth of it would fit.

    Why is this bad?
    The link is drawn and collides as a building-sized object, and mass properties from it
    are off by 1e6 (inertia) or 1e9 (volume).

    Example
    ```xml
    <link name="arm">
      <visual><geometry><mesh filename="package://arm/meshes/arm_mm.stl"/></geometry></visual>
    </link>
    ```

    Use instead:
    ```xml
    <link name="arm">
      <visual><geometry><mesh filename="package://arm/meshes/arm_mm.stl" scale="0.001 0.001 0.001"/></geometry></visual>
    </link>
    ```
    """
    if ctx.meshes is None:
        return

    entries = [(link, kind, index, ref, found.summary)
               for link, kind, index, ref, found in _lookups(ctx) if found.summary is not None]
    size = robot_size(robot)
    sizes = [_diagonal(summary) for *_, summary in entries]
    for (link, kind, index, ref, summary), diagonal in zip(entries, sizes):
        others = sizes[:]
        others.remove(diagonal)
        if looks_like_millimetres(diagonal, size, others):
            element = _element(link, kind, index)
            scaled = " ".join(f"{v * 0.001:g}" for v in ref.scale)
            yield Finding(f"'{ref.filename}' is {diagonal:.4g} m across, while the robot's "
                          f"joints span {size:.3g} m: it looks like millimetres (add "
                          'scale="0.001 0.001 0.001" or re-export in metres)', ref.where,
                          element,
                          changes=(ValueChange(f"{element}/geometry/mesh", "scale", scaled),))


def _diagonal(summary: MeshSummary) -> float:
    x, y, z = summary.extent
    return math.sqrt(x * x + y * y + z * z)


def _small_fixed_part(parents: dict[str, Joint], link: Link, summary: MeshSummary | None
                      ) -> bool:
    """A small part on a fixed joint (see SMALL_PART_SIZE); a root link never is one."""
    joint = parents.get(link.name)
    return (joint is not None and joint.type == "fixed" and summary is not None
            and _diagonal(summary) <= SMALL_PART_SIZE)


def _health_findings(robot: Robot, ctx: RuleContext, check: HealthCheck) -> Iterator[Finding]:
    """Findings of `check` on the meshes a result depends on: collision meshes of a
    description a simulator runs (one declaring masses: `is_dynamics_model`), and visual
    meshes whose volume feeds an inertia (`_volume_used`), small fixed parts left out."""
    parents = parent_joint_of(robot)
    dynamics = is_dynamics_model(robot)
    for link, kind, index, ref, found in _lookups(ctx, physical_only=True):
        if kind == "collision" and not dynamics:
            continue
        if _small_fixed_part(parents, link, found.summary):
            continue
        if found.summary is not None:
            message = check(found.summary)
            if message:
                yield Finding(f"'{ref.filename}' ({kind} of '{link.name}') {message}",
                              ref.where, _element(link, kind, index))


@rule("M109", "mesh-not-watertight", family=FAMILY, severity=Severity.WARNING, needs=NEEDS,
      opt_in=True)
def mesh_not_watertight(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a mesh whose volume robotdesc uses that is not closed: it has holes (boundary
    edges) or edges shared by more than two faces.

    Opt-in since issue 29: on the blind part 0 of 5 were worth fixing (holes of a few edges
    that change no result; docs/precision.md).

    The meshes judged are those a result depends on: collision meshes of a description a
    simulator runs (one that declares masses), and visual meshes of a link with a mass whose
    inertia is judged from them (the configured `inertia-source` is "visual", or the link
    has no collision geometry); a visual mesh of a link without `<inertial>` is never
    reported, nor a small part on a fixed joint (a mesh under 20 cm across, which Gazebo
    lumps into its parent). M110 and M111 judge the same meshes. Vertices on the rims of
    holes closer than a millionth of the mesh's size are merged first: exporters' rounding
    leaves such cracks, and no consumer sees them. A mesh with no hole whose only defect is edges shared by more than two faces, and whose volume
    is still integrated exactly, is not reported (Unitree G1's exports have a few).

    The message says how its mass properties were obtained instead (holes capped, or the
    convex hull).

    Why is this bad?
    An open surface has no inside: its volume, centre of mass and inertia are undefined,
    and physics engines that test for penetration (Bullet's GImpact, signed distance
    fields) give wrong contacts.

    Example
    ```xml
    <link name="arm">
      <collision><geometry><mesh filename="package://arm/meshes/arm_open.stl"/></geometry></collision>
    </link>
    ```

    Use instead (a closed mesh, for example `robotdesc collision`'s output):
    ```xml
    <link name="arm">
      <collision><geometry><mesh filename="package://arm/meshes/arm_closed.stl"/></geometry></collision>
    </link>
    ```
    """
    def check(summary: MeshSummary) -> str | None:
        health = summary.health
        if health.watertight or (not health.boundary_edges
                                 and summary.method is MassMethod.EXACT):
            return None  # closed, with edges shared by more faces: its volume is exact
        parts = []
        if health.boundary_edges:
            parts.append(f"{health.boundary_edges} boundary edges in {health.hole_loops} holes")
        if health.nonmanifold_edges:
            parts.append(f"{health.nonmanifold_edges} non-manifold edges")
        return (f"is not watertight ({', '.join(parts)}); mass properties: "
                f"{summary.method.value}")

    yield from _health_findings(robot, ctx, check)


@rule("M110", "mesh-inconsistent-winding", family=FAMILY, severity=Severity.WARNING,
      needs=NEEDS, opt_in=True)
def mesh_inconsistent_winding(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a collision mesh whose neighbouring faces disagree on their orientation.

    Opt-in since issue 29: on the blind part 0 of 5 were worth fixing (industrial arms'
    collision meshes, used by planners that ignore the winding; docs/precision.md).

    Why is this bad?
    Normals flip from face to face: engines that read face normals get contacts pushing
    the wrong way, and the volume integral is meaningless (robotdesc falls back to the
    convex hull).

    Example
    ```xml
    <link name="arm">
      <collision><geometry><mesh filename="package://arm/meshes/arm_mixed.stl"/></geometry></collision>
    </link>
    ```

    Use instead (re-oriented, e.g. MeshLab's "Re-Orient all faces coherently"):
    ```xml
    <link name="arm">
      <collision><geometry><mesh filename="package://arm/meshes/arm_oriented.stl"/></geometry></collision>
    </link>
    ```
    """
    def check(summary: MeshSummary) -> str | None:
        if summary.health.consistent_winding:
            return None
        return (f"has {summary.health.misoriented_edges} edges where the winding flips; "
                f"mass properties: {summary.method.value}")

    yield from _health_findings(robot, ctx, check)


@rule("M111", "mesh-inverted", family=FAMILY, severity=Severity.WARNING, needs=NEEDS)
def mesh_inverted(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a closed collision mesh whose faces all point inward (a negative volume).

    The volume must be at least 1% of the mesh's bounding box: a surface that encloses
    (almost) nothing, an open sheet or a flat part, has a volume whose sign is rounding,
    not an orientation.

    Why is this bad?
    Engines treat the outside as the inside: contacts pull objects in instead of pushing
    them out, and tools that trust the winding compute a negative mass.

    Example
    ```xml
    <link name="arm">
      <collision><geometry><mesh filename="package://arm/meshes/arm_inside_out.stl"/></geometry></collision>
    </link>
    ```

    Use instead (faces flipped):
    ```xml
    <link name="arm">
      <collision><geometry><mesh filename="package://arm/meshes/arm.stl"/></geometry></collision>
    </link>
    ```
    """
    def check(summary: MeshSummary) -> str | None:
        box = summary.extent[0] * summary.extent[1] * summary.extent[2]
        if (summary.signed_volume < 0 and summary.health.encloses_volume
                and -summary.signed_volume >= INVERTED_VOLUME_FRACTION * box > 0):
            return (f"is inverted: its faces point inward (signed volume "
                    f"{summary.signed_volume:.4g} m^3, {-summary.signed_volume / box:.0%} of "
                    "its bounding box)")
        return None

    yield from _health_findings(robot, ctx, check)


@rule("M112", "mesh-degenerate-faces", family=FAMILY, severity=Severity.INFO, needs=NEEDS,
      opt_in=True)
def mesh_degenerate_faces(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a collision mesh with degenerate faces (a repeated vertex or no area), or one
    that encloses no volume at all. Opt-in (info): no consumer is hurt by a few zero-area
    faces, and the blind sample of issue 29 judged them noise.

    Why is this bad?
    Zero-area faces have no normal: collision checkers skip them or divide by zero, and
    they are a sign of a careless export.

    Example
    ```xml
    <link name="arm">
      <collision><geometry><mesh filename="package://arm/meshes/arm_raw_export.stl"/></geometry></collision>
    </link>
    ```

    Use instead (cleaned):
    ```xml
    <link name="arm">
      <collision><geometry><mesh filename="package://arm/meshes/arm_clean.stl"/></geometry></collision>
    </link>
    ```
    """
    def check(summary: MeshSummary) -> str | None:
        if summary.properties is None:
            return "encloses no volume (all its points are coplanar)"
        count = summary.health.degenerate_faces
        if count:
            return (f"has {count} degenerate faces (of {summary.health.triangles})")
        return None

    yield from _health_findings(robot, ctx, check)


@rule("M113", "collision-uses-visual-mesh", family=FAMILY, severity=Severity.WARNING,
      needs=NEEDS, opt_in=True)
def collision_uses_visual_mesh(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a collision geometry that is the link's visual mesh file itself, when that
    mesh has more triangles than the collision budget. A small part on a fixed joint (a mesh
    under 20 cm across: a camera, a sensor housing) is not reported: Gazebo lumps it into
    its parent and its contacts cost little.

    Opt-in since issue 29: on the blind part 2 of 5 were worth fixing (meshes just over the
    budget; docs/precision.md).

    Why is this bad?
    Visual meshes are detailed for looks; as collision geometry they make every contact
    query slow. The Engineer robot's authors measured a real-time factor of 0.2 in Gazebo
    with visual meshes as collision, against 1 with simple shapes.

    Example
    ```xml
    <link name="arm">
      <visual><geometry><mesh filename="package://arm/meshes/arm.dae"/></geometry></visual>
      <collision><geometry><mesh filename="package://arm/meshes/arm.dae"/></geometry></collision>
    </link>
    ```

    Use instead (a simplified mesh or primitives; `robotdesc collision` makes them):
    ```xml
    <link name="arm">
      <visual><geometry><mesh filename="package://arm/meshes/arm.dae"/></geometry></visual>
      <collision><geometry><mesh filename="package://arm/meshes/arm_collision.stl"/></geometry></collision>
    </link>
    ```
    """
    if ctx.meshes is None:
        return
    budget = ctx.meshes.settings.collision_triangle_budget
    visual_paths: dict[str, set[str]] = {}
    entries = list(_lookups(ctx))
    for link, kind, _index, _ref, found in entries:
        if kind == "visual" and found.resolution.ok and found.resolution.path is not None:
            visual_paths.setdefault(link.name, set()).add(found.resolution.path)
    parents = parent_joint_of(robot)
    for link, kind, index, ref, found in entries:
        if kind != "collision" or not found.resolution.ok:
            continue
        if _small_fixed_part(parents, link, found.summary):
            continue
        if found.resolution.path in visual_paths.get(link.name, ()):
            triangles = found.summary.health.triangles if found.summary else 0
            if triangles > budget:
                yield Finding(f"collision of '{link.name}' uses its visual mesh "
                              f"'{ref.filename}' ({triangles} triangles, budget {budget}): "
                              "use a simplified mesh or primitives", ref.where,
                              _element(link, kind, index))


@rule("M114", "collision-mesh-over-budget", family=FAMILY, severity=Severity.WARNING,
      needs=NEEDS, opt_in=True)
def collision_mesh_over_budget(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a collision mesh with more triangles than the budget
    (`[tool.robotdesc.meshes] collision-triangle-budget`, 10 000 by default) that is not
    the link's visual mesh (that case is M113's). Small parts on fixed joints are left out,
    as in M113.

    Opt-in since issue 29: on the blind part 2 of 5 were worth fixing (meshes just over the
    budget; docs/precision.md).

    Why is this bad?
    Collision checking costs grow with the triangle count; a physics engine steps slower
    than real time and a planner's collision checks dominate its run time.

    Example
    ```xml
    <link name="arm">
      <collision><geometry><mesh filename="package://arm/meshes/arm_fine.stl"/></geometry></collision>
    </link>
    ```

    Use instead:
    ```xml
    <link name="arm">
      <collision><geometry><mesh filename="package://arm/meshes/arm_decimated.stl"/></geometry></collision>
    </link>
    ```
    """
    if ctx.meshes is None:
        return
    budget = ctx.meshes.settings.collision_triangle_budget
    entries = list(_lookups(ctx))
    visual_paths = {(link.name, found.resolution.path) for link, kind, _i, _r, found in entries
                    if kind == "visual" and found.resolution.ok}
    parents = parent_joint_of(robot)
    for link, kind, index, ref, found in entries:
        if kind != "collision" or found.summary is None:
            continue
        if (link.name, found.resolution.path) in visual_paths:
            continue
        if _small_fixed_part(parents, link, found.summary):
            continue
        triangles = found.summary.health.triangles
        if triangles > budget:
            yield Finding(f"collision mesh '{ref.filename}' of '{link.name}' has {triangles} "
                          f"triangles, over the budget of {budget}", ref.where,
                          _element(link, kind, index))


@rule("M115", "link-without-collision", family=FAMILY, severity=Severity.WARNING,
      opt_in=True)
def link_without_collision(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a link that has a `<visual>` but no `<collision>`, in a description meant for
    dynamics (one in which some moving link declares a mass). Placeholder links lighter
    than a gram are skipped.

    Off by default (`--select M115`): on real packages most such links are meant to have no
    collision (an IMU or laser housing inside the body, a rotor inside the leg, a decorative
    cover), so only a review of a whole robot's collision coverage should turn it on
    (docs/precision.md).

    Why is this bad?
    In simulation the link passes through the floor and through other links; planners do
    not avoid it. If that is intended (a decorative part), say so with a suppression.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/>
      <link name="arm">
        <inertial><mass value="1"/>
          <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
        <visual><geometry><box size="0.1 0.1 0.4"/></geometry></visual>
      </link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/>
      <link name="arm">
        <inertial><mass value="1"/>
          <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
        <visual><geometry><box size="0.1 0.1 0.4"/></geometry></visual>
        <collision><geometry><box size="0.1 0.1 0.4"/></geometry></collision>
      </link>
      <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
    </robot>
    ```
    """
    if not is_dynamics_model(robot):
        return
    for link in robot.links:
        dummy = link.inertial is not None and link.inertial.mass is not None \
            and link.inertial.mass < DUMMY_MASS
        if link.visuals and not link.collisions and not dummy:
            yield Finding(f"link '{link.name}' has {len(link.visuals)} visual(s) but no "
                          "collision: it passes through everything in simulation",
                          link.where, f"link:{link.name}")
