"""The per-link inertia table of `robotdesc inertia`: declared against geometry-derived.

Units: kg, m, m^3, kg/m^3, kg*m^2. Mass properties from geometry assume uniform density at
the declared mass (the geometry alone says nothing about mass, only about its distribution).
"""

from __future__ import annotations

import os
import textwrap
from collections.abc import Sequence
from dataclasses import dataclass

from robotdesc.inertia.compare import compare_inertia
from robotdesc.inertia.mesh_access import MeshAccess
from robotdesc.model.elements import Robot
from robotdesc.spatial import Vec3, principal_moments

#: A row as JSON: numbers, strings, lists of numbers, lists of strings, or null.
JsonValue = float | str | list[float] | list[str] | None


@dataclass(frozen=True)
class InertiaRow:
    """One link of the table.

    Attributes:
        link: the link's name.
        source: geometry measured ("collision", "visual", "" for none).
        declared_mass: kg, None when not declared.
        volume: m^3 of the measured geometry, None when not measured.
        density: declared mass / volume (kg/m^3), None when either is missing.
        declared_com / derived_com: centre of mass in the link frame (m).
        declared_moments / derived_moments: principal moments, ascending (kg*m^2); the
            derived ones at the declared mass.
        error: the largest relative difference of a principal moment or of the whole tensor
            (so a tensor with the right moments about the wrong axes counts), None if not
            compared.
        cause: the likely cause of a difference, when one is recognised.
        notes: how the geometry was measured, and what could not be.
        suppressed: the codes of lint's inertia findings on this link that a suppression
            (inline comment, per-file ignore, baseline) hides; empty when none
            (`robotdesc.linting.verdict`): the tensor is meant as it is.
    """

    link: str
    source: str
    declared_mass: float | None
    volume: float | None
    density: float | None
    declared_com: Vec3 | None
    derived_com: Vec3 | None
    declared_moments: Vec3 | None
    derived_moments: Vec3 | None
    error: float | None
    cause: str | None
    notes: tuple[str, ...] = ()
    suppressed: tuple[str, ...] = ()

    def to_json(self) -> dict[str, JsonValue]:
        """The row as JSON, one key per attribute (tuples as lists)."""
        return {"link": self.link, "source": self.source, "declared_mass": self.declared_mass,
                "volume": self.volume, "density": self.density,
                "declared_com": _list(self.declared_com), "derived_com": _list(self.derived_com),
                "declared_moments": _list(self.declared_moments),
                "derived_moments": _list(self.derived_moments), "error": self.error,
                "cause": self.cause, "notes": list(self.notes),
                "suppressed": list(self.suppressed)}


@dataclass(frozen=True)
class InertiaTable:
    """Declared against mesh-derived inertia for every link (what `robotdesc.mesh_inertia`
    returns): a table in Jupyter, plain text elsewhere, `to_dict()` for JSON.

    Attributes:
        target: the description file.
        source: the geometry measured ("collision" or "visual").
        rows: one per link that declares an inertial or has geometry.
    """

    target: str
    source: str
    rows: tuple[InertiaRow, ...]

    def row(self, link: str) -> InertiaRow | None:
        return next((row for row in self.rows if row.link == link), None)

    def to_dict(self) -> dict[str, str | list[dict[str, JsonValue]]]:
        return {"target": self.target, "source": self.source,
                "links": [row.to_json() for row in self.rows]}

    def __str__(self) -> str:
        return render_table(list(self.rows))

    def __repr__(self) -> str:
        """A one-line summary (`str()` is the whole table; Jupyter draws it)."""
        off = sum(1 for row in self.rows if row.error is not None and row.error > 0.5)
        return (f"<InertiaTable {os.path.basename(self.target)!r} ({self.source} geometry): "
                f"{len(self.rows)} links, {off} differing by more than 50 %>")

def inertia_table(robot: Robot, meshes: MeshAccess, tolerance: float = 0.5) -> list[InertiaRow]:
    """One row per link that declares an inertial or has geometry."""

    rows: list[InertiaRow] = []
    for link in robot.links:
        inertial = link.inertial
        geometry = meshes.link_geometry(link)
        if inertial is None and geometry.properties is None:
            continue
        mass = inertial.mass if inertial is not None else None
        props = geometry.properties
        volume = props.volume if props is not None else None
        density = mass / volume if mass is not None and volume else None
        declared_moments = (principal_moments(inertial.inertia.matrix())
                            if inertial is not None and inertial.inertia is not None else None)
        derived_moments: Vec3 | None = None
        error: float | None = None
        cause: str | None = None
        if props is not None and mass is not None and mass > 0:
            derived_moments = props.scaled_to_mass(mass).principal_moments()
            if inertial is not None and declared_moments is not None and geometry.trusted:
                comparison = compare_inertia(inertial, props, tolerance)
                error = max(*comparison.moment_errors, comparison.tensor_error)
                cause = comparison.cause
        notes = geometry.notes + tuple(f"not measured: {u}" for u in geometry.unmeasured)
        rows.append(InertiaRow(
            link.name, geometry.source, mass, volume, density,
            inertial.origin.xyz if inertial is not None else None,
            props.center_of_mass if props is not None else None,
            declared_moments, derived_moments, error, cause, notes))
    return rows


def render_table(rows: list[InertiaRow]) -> str:
    """The rows as a text table that fits 100 columns: one line per link (mass kg, volume
    m^3, density kg/m^3, error), then its centre of mass (m) and principal moments (kg m^2),
    declared and from the geometry, and its notes, indented below."""
    header = ("LINK", "SOURCE", "MASS kg", "VOLUME m^3", "DENSITY", "ERROR")
    cells = [header]
    for row in rows:
        error = "-" if row.error is None else f"{100 * row.error:.3g}%"
        cells.append((row.link, row.source or "-", _num(row.declared_mass), _num(row.volume),
                      _num(row.density), error + (" suppressed" if row.suppressed else "")))
    widths = [max(len(line[i]) for line in cells) for i in range(len(header))]
    out = ["  ".join(c.ljust(w) for c, w in zip(header, widths)).rstrip()]
    for row, line in zip(rows, cells[1:]):
        out.append("  ".join(c.ljust(w) for c, w in zip(line, widths)).rstrip())
        out.append(f"    COM m          declared {_vec(row.declared_com):<29} "
                   f"geometry {_vec(row.derived_com)}".rstrip())
        out.append(f"    moments kg m^2 declared {_vec(row.declared_moments):<29} "
                   f"geometry {_vec(row.derived_moments)}".rstrip())
        said = ((f"suppressed in lint ({', '.join(row.suppressed)}): meant as it is",)
                if row.suppressed else ())
        for note in said + ((f"likely cause: {row.cause}",) if row.cause else ()) + row.notes:
            out.extend(textwrap.wrap(note, 100, initial_indent="    ",
                                     subsequent_indent="      ", break_on_hyphens=False))
    return "\n".join(out) + "\n"


def _num(value: float | None) -> str:
    return "-" if value is None else f"{value:.4g}"


def _list(values: Vec3 | None) -> list[float] | None:
    return list(values) if values is not None else None


def _vec(values: Sequence[float] | None) -> str:
    return "-" if values is None else " ".join(f"{v:.4g}" for v in values)
