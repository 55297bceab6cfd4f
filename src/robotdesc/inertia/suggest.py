"""Suggested `<inertial>` blocks from a link's geometry, in a form that reads well in both
URDF and xacro (plain attributes, six significant digits, rpy zero: the tensor is written in
link axes about the centre of mass).

Units: kg, m, kg*m^2.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TypeVar

from robotdesc.inertia.mesh_access import MeshAccess
from robotdesc.inertia.table import InertiaRow, inertia_table
from robotdesc.mesh.context import LinkGeometry, MeshContext
from robotdesc.mesh.properties import MassProperties
from robotdesc.mesh.scale_check import looks_like_millimetres, robot_size
from robotdesc.model.elements import Collision, Link, MeshRef, Robot, Visual
from robotdesc.model.tree import parent_joint_of
from robotdesc.source import Span

#: The scale that turns a mesh exported in millimetres into metres.
MILLIMETRE = 0.001

#: A `<visual>` or a `<collision>`.
ShapeT = TypeVar("ShapeT", Visual, Collision)

#: The density assumed when a link declares no usable mass (kg/m^3): a guess, said so.
FALLBACK_DENSITY = 1000.0
#: Denser than any material (osmium: 22,590 kg/m^3): geometry that would hold the declared
#: mass at more than this is a stand-in, not the body, and no tensor is suggested from it.
MAX_DENSITY = 25_000.0


def denser_than_any_material(density: float | None) -> bool:
    """Whether a declared mass in its geometry (kg/m^3, None: unknown) would be denser than
    any material: the geometry is a stand-in, not the body."""
    return density is not None and density > MAX_DENSITY


@dataclass(frozen=True)
class Suggestion:
    """A corrected `<inertial>` for one link.

    Attributes:
        link: the link's name.
        block: the `<inertial>` element's text (no indentation, newline separated).
        properties: the mass properties written in the block (link frame).
        replaces: where the declared `<inertial>` starts (None: the link has none; the
            block goes inside the `<link>`).
        link_span: where the `<link>` starts.
        mass_source: "declared" or a note on how the mass was guessed.
        in_macro: the declared block is written inside a xacro macro (its text is shared
            by every call of the macro).
    """

    link: str
    block: str
    properties: MassProperties
    replaces: Span | None
    link_span: Span | None
    mass_source: str = "declared"
    in_macro: bool = False


def suggest_inertial(link: Link, geometry: MassProperties,
                     fallback_density: float = FALLBACK_DENSITY,
                     note: str | None = None) -> Suggestion:
    """The `<inertial>` of `link` computed from its geometry (at density 1, link frame).

    The declared mass is kept when it is positive; otherwise the geometry's volume times
    `fallback_density` is used, and the block says so in a comment. `note` (for example
    "add the scale to these meshes") is written as a comment too.
    """
    declared = link.inertial.mass if link.inertial is not None else None
    if declared is not None and declared > 0:
        body, source = geometry.scaled_to_mass(declared), "declared"
    else:
        body = geometry.with_density(fallback_density)
        source = (f"guessed: volume {geometry.volume:.6g} m^3 x {fallback_density:g} kg/m^3; "
                  "replace with the real mass")
    where = link.inertial.where if link.inertial is not None else None
    in_macro = bool(where and where.macro_stack) or bool(link.where and link.where.macro_stack)
    comment = "; ".join(c for c in (None if source == "declared" else f"mass {source}", note)
                        if c) or None
    return Suggestion(link.name, format_inertial(body, comment),
                      body, where.span if where else None,
                      link.where.span if link.where else None, source, in_macro)


def millimetre_meshes(robot: Robot, meshes: MeshAccess, link: Link,
                      source: str) -> tuple[MeshRef, ...]:
    """The link's `<mesh>` references of `source` ("collision" or "visual") that look like
    millimetres (M108's test: about 1000 times larger than the robot)."""
    shapes = link.collisions if source == "collision" else link.visuals
    refs = [s.geometry for s in shapes if isinstance(s.geometry, MeshRef)]
    if not refs:
        return ()
    diagonals: dict[int, float] = {}
    for _, _, _, _, ref in meshes.meshes():
        summary = meshes.lookup(ref).summary
        if summary is not None:
            x, y, z = summary.extent
            diagonals[id(ref)] = (x * x + y * y + z * z) ** 0.5
    size = robot_size(robot)
    found: list[MeshRef] = []
    for ref in refs:
        own = diagonals.get(id(ref))
        if own is None:
            continue
        others = [d for key, d in diagonals.items() if key != id(ref)]
        if looks_like_millimetres(own, size, others):
            found.append(ref)
    return tuple(found)


def corrected_geometry(robot: Robot, meshes: MeshAccess, link: Link,
                       geometry: LinkGeometry) -> tuple[LinkGeometry, str | None]:
    """The link's geometry with meshes diagnosed as millimetres scaled by 0.001, and a note
    that says so (the geometry itself and None when no mesh is in millimetres)."""
    wrong = millimetre_meshes(robot, meshes, link, geometry.source) if geometry.source else ()
    if not wrong:
        return geometry, None
    ids = {id(ref) for ref in wrong}
    scaled_link = dataclasses.replace(link, visuals=_scaled(link.visuals, ids),
                                      collisions=_scaled(link.collisions, ids))
    context = MeshContext(robot, meshes.settings, meshes.find_package)
    measured = context.link_geometry(scaled_link, geometry.source)
    if not measured.trusted:
        return geometry, None
    names = ", ".join(sorted({ref.filename for ref in wrong}))
    return measured, (f"{names} look(s) like millimetres: add scale=\"0.001 0.001 0.001\" to "
                      "the <mesh>; this block assumes it")


def _scaled(shapes: tuple[ShapeT, ...], ids: set[int]) -> tuple[ShapeT, ...]:
    """The shapes, those whose `<mesh>` is one of `ids` scaled by MILLIMETRE."""
    return tuple(_scaled_shape(shape) if id(shape.geometry) in ids else shape
                 for shape in shapes)


def _scaled_shape(shape: ShapeT) -> ShapeT:
    geometry = shape.geometry
    if not isinstance(geometry, MeshRef):
        return shape
    x, y, z = geometry.scale
    return dataclasses.replace(shape, geometry=dataclasses.replace(
        geometry, scale=(x * MILLIMETRE, y * MILLIMETRE, z * MILLIMETRE)))


def suggest_for_link(robot: Robot, meshes: MeshAccess, link: Link,
                     fallback_density: float = FALLBACK_DENSITY) -> Suggestion | None:
    """The suggested `<inertial>` of one link from its measured geometry, with meshes in
    millimetres scaled first; None when the geometry cannot be trusted, or cannot be the
    body: the declared mass in it would be denser than any material (`MAX_DENSITY`)."""
    geometry = meshes.link_geometry(link)
    if not geometry.trusted:
        return None
    geometry, note = corrected_geometry(robot, meshes, link, geometry)
    if geometry.properties is None:  # trusted geometry has properties
        return None
    declared = link.inertial.mass if link.inertial is not None else None
    volume = geometry.properties.volume
    if declared is not None and declared > 0 and volume > 0 \
            and denser_than_any_material(declared / volume):
        return None  # a stand-in (a 2 cm stub under a 3 kg link) is not the body
    return suggest_inertial(link, geometry.properties, fallback_density, note)


def format_inertial(body: MassProperties, comment: str | None = None) -> str:
    """The `<inertial>` element for a body (mass kg, COM m, inertia kg*m^2 in link axes)."""
    (ixx, ixy, ixz), (_, iyy, iyz), (_, _, izz) = body.inertia
    floor = 1e-9 * max(abs(ixx), abs(iyy), abs(izz))  # products at rounding noise become 0
    ixy, ixz, iyz = (0.0 if abs(v) <= floor else v for v in (ixy, ixz, iyz))
    lines = ["<inertial>"]
    if comment:
        lines.append(f"  <!-- {comment.replace('--', '-')} -->")
    lines += [
        f'  <origin xyz="{_vec(body.center_of_mass)}" rpy="0 0 0"/>',
        f'  <mass value="{_num(body.mass)}"/>',
        (f'  <inertia ixx="{_num(ixx)}" ixy="{_num(ixy)}" ixz="{_num(ixz)}" '
         f'iyy="{_num(iyy)}" iyz="{_num(iyz)}" izz="{_num(izz)}"/>'),
        "</inertial>",
    ]
    return "\n".join(lines)


def _num(value: float) -> str:
    """Six significant digits; tiny values relative to rounding become 0."""
    if abs(value) < 1e-15:
        return "0"
    text = f"{value:.6g}"
    return "0" if text in ("-0", "0") else text


def _vec(values: Sequence[float]) -> str:
    return " ".join(_num(v) for v in values)


def select_suggestions(robot: Robot, meshes: MeshAccess, rows: Sequence[InertiaRow] | None = None,
                       everything: bool = False, tolerance: float = 0.5) -> list[Suggestion]:
    """The suggestions `robotdesc inertia --suggest` prints and `--write` patches.

    A link is chosen when its geometry can be trusted and it has no declared inertia, or its
    declared tensor differs from the geometry's beyond `tolerance` in its principal moments
    or as a whole (a rotated tensor: right moments, wrong axes); every measured link with
    `everything`. A link without `<inertial>` that is a root (the massless root the
    consumers expect, KDL warns about a root's inertia) or hangs on a fixed joint (a frame,
    lumped into its parent) is left as it is. Meshes diagnosed as millimetres are scaled
    first (see `suggest_for_link`). A row marked `suppressed` (lint's finding on the link is
    suppressed: `robotdesc.linting.verdict`) is left out unless `everything`.

    Args:
        rows: the inertia table (`robotdesc.inertia.table.inertia_table`), computed when None.
    """
    table = rows if rows is not None else inertia_table(robot, meshes, tolerance)
    errors = {row.link: row.error for row in table}
    meant = {row.link for row in table if row.suppressed}
    parents = parent_joint_of(robot)
    found: list[Suggestion] = []
    for link in robot.links:
        if link.name not in errors:
            continue
        parent = parents.get(link.name)
        if link.inertial is None and (parent is None or parent.type == "fixed"):
            continue  # a massless root or a frame: no mass is what it should have
        error = errors[link.name]
        if not everything and link.inertial is not None and error is not None \
                and error <= tolerance:
            continue
        if not everything and link.name in meant:
            continue  # lint's finding on it is suppressed: the tensor is meant
        suggestion = suggest_for_link(robot, meshes, link)
        if suggestion is not None:
            found.append(suggestion)
    return found
