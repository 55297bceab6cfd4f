"""What linting one file produces."""

from __future__ import annotations

import html
import os
from dataclasses import dataclass
from typing import TYPE_CHECKING

from robotdesc.diagnostics import Diagnostic, Severity
from robotdesc.errors import InputError, RuleCrashed
from robotdesc.output import RunInputs

if TYPE_CHECKING:  # the model is not imported by a lint answered from the result cache
    from robotdesc.expansion.result import Expanded
    from robotdesc.model.elements import Robot

__all__ = ["LintFailure", "LintResult", "RuleCrashed"]  # RuleCrashed: robotdesc.errors

#: Diagnostics drawn in a notebook's table (a notebook stays small; all are in the result).
_HTML_ROWS = 500


@dataclass(frozen=True)
class LintResult:
    """The outcome of linting one file.

    Attributes:
        target: the linted file (absolute path).
        diagnostics: what was found, sorted by file, line and code.
        expanded: the expansion (None: dropped, e.g. read from the result cache).
        robot: the parsed model (None: dropped).
        suppressed: how many findings inline comments suppressed.
        config_path: the config file that applied (None: defaults).
        rules_run: the codes of the rules that ran.
        variant: the matrix arguments of this variant as (name, value) pairs (empty: the
            target is not a matrix variant); see robotdesc.linting.matrix.
        inputs: the files the lint read (`robotdesc.output.RunInputs`; kept when
            `expanded` and `robot` are dropped): no output of the run may replace one.
        args: the xacro arguments the target was linted with (config target and command
            line), as (name, value) pairs; empty: the file's defaults.
        suppressed_by_config: findings hidden by the config's per-file ignores.
        suppressed_by_baseline: findings hidden by a baseline file.
        hidden: the findings suppressed (inline comments, per-file ignores, baseline), for the
            commands that must give lint's verdict (`robotdesc.linting.verdict`).
    """

    target: str
    diagnostics: tuple[Diagnostic, ...]
    expanded: Expanded | None = None
    robot: Robot | None = None
    suppressed: int = 0
    config_path: str | None = None
    rules_run: tuple[str, ...] = ()
    variant: tuple[tuple[str, str], ...] = ()
    inputs: RunInputs | None = None
    args: tuple[tuple[str, str], ...] = ()
    suppressed_by_config: int = 0
    suppressed_by_baseline: int = 0
    hidden: tuple[Diagnostic, ...] = ()

    @property
    def files_read(self) -> frozenset[str]:
        """The files the lint read, as absolute real paths (the description, its includes,
        the config, package.xml files and meshes when `inputs` is known; else the
        description and what its expansion read)."""
        if self.inputs is not None:
            return frozenset(item.path for item in self.inputs.items)
        paths = [self.target, self.config_path]
        if self.expanded is not None:
            paths += [*self.expanded.files, *self.expanded.files_read]
        return frozenset(os.path.realpath(p) for p in paths if p)

    @property
    def counts(self) -> dict[Severity, int]:
        """The number of diagnostics per severity, worst first (every severity is a key)."""
        counts = {level: 0 for level in sorted(Severity, reverse=True)}
        for diagnostic in self.diagnostics:
            counts[diagnostic.severity] += 1
        return counts

    def failed(self, fail_on: Severity = Severity.INFO) -> bool:
        """Whether any diagnostic is at or above `fail_on`."""
        return any(d.severity >= fail_on for d in self.diagnostics)

    def __repr__(self) -> str:
        counts = ", ".join(f"{n} {level}" for level, n in self.counts.items())
        return f"<LintResult {self.target!r}: {counts}>"

    def _repr_html_(self) -> str:
        """An HTML table of the diagnostics (for Jupyter; the first 500, then a count)."""
        shown = self.diagnostics[:_HTML_ROWS]
        more = len(self.diagnostics) - len(shown)
        rows = "".join(
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>".format(
                *(html.escape(str(cell)) for cell in (
                    d.where.span if d.where else "", d.code, d.name, d.severity, d.message)))
            for d in shown)
        if more:
            rows += f'<tr><td colspan="5">... {more} more (see .diagnostics)</td></tr>'
        head = ("<tr><th>location</th><th>code</th><th>rule</th><th>severity</th>"
                "<th>message</th></tr>")
        caption = html.escape(repr(self))
        return f"<table><caption>{caption}</caption>{head}{rows}</table>"


@dataclass(frozen=True)
class LintFailure:
    """A file that could not be checked (exit code 2).

    Attributes:
        target: the file as given.
        error: why (an `InputError`, carrying file:line and the macro call chain).
        variant: the matrix arguments of the variant that failed (empty: not a variant).
    """

    target: str
    error: InputError
    variant: tuple[tuple[str, str], ...] = ()
