"""Diagnostics: what a rule reports, with its severity and its source."""

from __future__ import annotations

import enum
from dataclasses import dataclass

from robotdesc.source import Provenance


class Severity(enum.IntEnum):
    """How bad a finding is; the order is used by `--fail-on`."""

    INFO = 1
    WARNING = 2
    ERROR = 3

    def __str__(self) -> str:
        return self.name.lower()

    @classmethod
    def parse(cls, text: str) -> "Severity":
        try:
            return cls[text.strip().upper()]
        except KeyError:
            raise ValueError(f"unknown severity '{text}' (expected error, warning or info)")


@dataclass(frozen=True)
class ValueChange:
    """A fix's request, made by the rule where it finds the problem: set `attribute` of the
    expanded element named `element` to `value`. The edit engine (robotdesc.edit) finds
    where the value is written in the sources, from the provenance the expansion recorded.

    Attributes:
        element: the element's line-free name, the diagnostic's or a path below it, e.g.
            "joint:elbow/limit", "link:arm/collision[0]/geometry/mesh".
        tolerance: relative; a written number this close to the new one keeps its text.
    """

    element: str
    attribute: str
    value: str
    tolerance: float = 1e-9


@dataclass(frozen=True)
class Finding:
    """What a rule's check yields: the rule fills in code, name and severity.

    Attributes:
        message: what is wrong, with the numbers.
        where: the provenance of the offending element (None for robot-wide findings
            that have no better place; the robot's own provenance is used then).
        element: a stable, line-free name of the element, e.g. "joint:shoulder".
        fix: suggested replacement text (for example a corrected `<inertial>` block).
        changes: the fix as data: the attribute values to set (`lint --fix` applies them
            when the rule's code is in rules/fixes.py's FIXABLE).
        unfixable: why the rule's fix cannot be made for this finding (e.g. "'/opt/a.stl'
            is in no ROS package"); empty when it can, or the rule has no fix.
    """

    message: str
    where: Provenance | None = None
    element: str = ""
    fix: str | None = None
    changes: tuple[ValueChange, ...] = ()
    unfixable: str = ""


@dataclass(frozen=True)
class Diagnostic:
    """One reported problem.

    Attributes:
        code: stable rule code such as "J101".
        name: kebab-case rule name such as "revolute-without-limit".
        severity: the effective severity (after config overrides).
        message: what is wrong, with the numbers.
        where: the provenance (xacro source file:line and macro call chain).
        element: a stable, line-free name of the element, e.g. "joint:shoulder".
        fix: suggested replacement text, if any.
        target: the linted file (the top-level xacro/URDF).
        changes: the fix as data (the rule's `Finding.changes`).
        unfixable: why the fix cannot be made (the rule's `Finding.unfixable`).
    """

    code: str
    name: str
    severity: Severity
    message: str
    where: Provenance | None
    element: str = ""
    fix: str | None = None
    target: str = ""
    changes: tuple[ValueChange, ...] = ()
    unfixable: str = ""

    def sort_key(self) -> tuple[str, int, str, str]:
        span = self.where.span if self.where else None
        return (span.path if span else "", span.line if span else 0, self.code, self.message)
