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
class Finding:
    """What a rule's check yields: the rule fills in code, name and severity.

    Attributes:
        message: what is wrong, with the numbers.
        where: the provenance of the offending element (None for robot-wide findings
            that have no better place; the robot's own provenance is used then).
        element: a stable, line-free name of the element, e.g. "joint:shoulder".
        fix: suggested replacement text (for example a corrected `<inertial>` block).
    """

    message: str
    where: Provenance | None = None
    element: str = ""
    fix: str | None = None


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
    """

    code: str
    name: str
    severity: Severity
    message: str
    where: Provenance | None
    element: str = ""
    fix: str | None = None
    target: str = ""

    def sort_key(self) -> tuple[str, int, str, str]:
        span = self.where.span if self.where else None
        return (span.path if span else "", span.line if span else 0, self.code, self.message)
