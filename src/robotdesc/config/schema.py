"""What a robotdesc configuration holds: `Config`, `TargetSpec` and the keys of its table."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any

from robotdesc.diagnostics import Severity
from robotdesc.mesh.settings import MeshSettings

#: The keys of `[tool.robotdesc]` (robotdesc.toml's top level), in snake case.
KEYS = ("select", "ignore", "per_file_ignores", "rules", "severity", "fail_on", "packages",
        "args", "meshes", "targets", "sim")


@dataclass(frozen=True)
class TargetSpec:
    """A description the config asks `lint` to check, with its argument matrix.

    Attributes:
        file: the description (absolute path).
        args: fixed xacro arguments as (name, value) pairs.
        matrix: (argument, values) pairs; every combination is linted as its own variant.
    """

    file: str
    args: tuple[tuple[str, str], ...] = ()
    matrix: tuple[tuple[str, tuple[str, ...]], ...] = ()


@dataclass(frozen=True)
class SimSettings:
    """`[sim]`: settings of `robotdesc sim`.

    Attributes:
        separation_multiplier: (engine, multiplier) pairs: the drive test's
            `wheel_separation_multiplier` in that engine, replacing the one of the
            diff_drive_controller configuration (a skid-steered robot slips differently in
            each engine; the controllers file holds the value of the simulator it is for).
    """

    separation_multiplier: tuple[tuple[str, float], ...] = ()

    def separation_multiplier_for(self, engine: str) -> float | None:
        """The multiplier configured for `engine`, or None."""
        return dict(self.separation_multiplier).get(engine)


@dataclass(frozen=True)
class Config:
    """The settings that apply to one linted file.

    Attributes:
        path: the config file these settings come from (None: built-in defaults).
        select: rule selectors to enable (None: all rules).
        ignore: rule selectors to disable.
        per_file_ignores: (glob, selectors) pairs; globs are relative to the config's directory.
        rule_options: (code, options instance) pairs for rules configured in `rules.CODE`.
        severity: (code, severity) overrides.
        fail_on: the lowest severity that makes `lint` exit with 1.
        packages: (package name, absolute directory) pairs.
        args: default xacro arguments as (name, value) pairs.
        meshes: mesh and inertia settings.
        targets: the descriptions a directory lint checks (empty: discover them).
        sim: settings of `robotdesc sim`.
    """

    path: str | None = None
    select: tuple[str, ...] | None = None
    ignore: tuple[str, ...] = ()
    per_file_ignores: tuple[tuple[str, tuple[str, ...]], ...] = ()
    rule_options: tuple[tuple[str, Any], ...] = ()
    severity: tuple[tuple[str, Severity], ...] = ()
    fail_on: Severity = Severity.INFO
    packages: tuple[tuple[str, str], ...] = ()
    args: tuple[tuple[str, str], ...] = ()
    meshes: MeshSettings = field(default_factory=MeshSettings)
    targets: tuple[TargetSpec, ...] = ()
    sim: SimSettings = field(default_factory=SimSettings)

    @property
    def root(self) -> str:
        """The directory relative paths in this config are resolved against."""
        return os.path.dirname(self.path) if self.path else os.getcwd()

    def options_for(self, code: str) -> Any | None:
        """The configured options instance of rule `code`, or None when not configured."""
        return dict(self.rule_options).get(code)

    def severity_for(self, code: str, default: Severity) -> Severity:
        """The effective severity of rule `code`."""
        return dict(self.severity).get(code, default)
