"""The output formats of `robotdesc lint --format`: one table, read by the CLI and the docs.

Each renderer module is imported when its format is used (SARIF and JUnit read the rule
catalog, which is not needed for `robotdesc --help`).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from robotdesc.diagnostics import Severity

if TYPE_CHECKING:
    from robotdesc.linting.result import LintFailure, LintResult


@dataclass(frozen=True)
class ReportFormat:
    """One output format.

    Attributes:
        name: the value of `--format`.
        module: the module holding the renderer.
        function: the renderer: (results, failures[, fail_on]) -> text.
        summary: one line for `--help` and the docs.
        takes_fail_on: the renderer needs `--fail-on` (JUnit marks failing cases).
    """

    name: str
    module: str
    function: str
    summary: str
    takes_fail_on: bool = False

    def renderer(self) -> Callable[..., str]:
        """The rendering function (its module imported now)."""
        render: Callable[..., str] = getattr(importlib.import_module(self.module),
                                             self.function)
        return render


#: Every format, in the order `--help` lists them ("text" first: the default).
FORMATS: tuple[ReportFormat, ...] = (
    ReportFormat("text", "robotdesc.report.text", "render_text",
                 "findings with the source line and the macro call chain (the default)"),
    ReportFormat("json", "robotdesc.report.json", "render_json",
                 "a versioned JSON document (docs/json-format.md)"),
    ReportFormat("sarif", "robotdesc.report.sarif", "render_sarif",
                 "SARIF 2.1.0, for GitHub code scanning and other SARIF viewers"),
    ReportFormat("junit", "robotdesc.report.junit", "render_junit",
                 "JUnit XML, one test case per file and rule", takes_fail_on=True),
    ReportFormat("github", "robotdesc.report.github", "render_github",
                 "GitHub Actions workflow annotations"),
    ReportFormat("gitlab", "robotdesc.report.gitlab", "render_gitlab",
                 "GitLab Code Quality JSON"),
)

#: The names `--format` accepts.
FORMAT_NAMES: tuple[str, ...] = tuple(f.name for f in FORMATS)


def render_report(name: str, results: Sequence[LintResult], failures: Sequence[LintFailure],
                  fail_on: Severity) -> str:
    """The report of `results` and `failures` in the format called `name`.

    Raises:
        KeyError: no format has that name (the CLI's choices prevent it).
    """
    chosen = next(f for f in FORMATS if f.name == name)
    render = chosen.renderer()
    if chosen.takes_fail_on:
        return render(results, failures, fail_on=fail_on)
    return render(results, failures)
