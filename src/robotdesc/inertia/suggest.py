"""Suggested `<inertial>` blocks from a link's geometry, in a form that reads well in both
URDF and xacro (plain attributes, six significant digits, rpy zero: the tensor is written in
link axes about the centre of mass).

Units: kg, m, kg*m^2.
"""

from __future__ import annotations

from dataclasses import dataclass

from robotdesc.mesh.properties import MassProperties
from robotdesc.model.elements import Link
from robotdesc.source import Span

#: The density assumed when a link declares no usable mass (kg/m^3): a guess, said so.
FALLBACK_DENSITY = 1000.0


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
                     fallback_density: float = FALLBACK_DENSITY) -> Suggestion:
    """The `<inertial>` of `link` computed from its geometry (at density 1, link frame).

    The declared mass is kept when it is positive; otherwise the geometry's volume times
    `fallback_density` is used, and the block says so in a comment.
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
    return Suggestion(link.name, format_inertial(body, None if source == "declared" else source),
                      body, where.span if where else None,
                      link.where.span if link.where else None, source, in_macro)


def format_inertial(body: MassProperties, comment: str | None = None) -> str:
    """The `<inertial>` element for a body (mass kg, COM m, inertia kg*m^2 in link axes)."""
    (ixx, ixy, ixz), (_, iyy, iyz), (_, _, izz) = body.inertia
    floor = 1e-9 * max(abs(ixx), abs(iyy), abs(izz))  # products at rounding noise become 0
    ixy, ixz, iyz = (0.0 if abs(v) <= floor else v for v in (ixy, ixz, iyz))
    lines = ["<inertial>"]
    if comment:
        lines.append(f"  <!-- mass {comment.replace('--', '-')} -->")
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


def _vec(values) -> str:
    return " ".join(_num(v) for v in values)
