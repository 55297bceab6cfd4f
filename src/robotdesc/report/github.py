"""GitHub Actions workflow commands: one annotation per finding, shown on the pull request.

    ::error file=urdf/arm.xacro,line=3,col=2,title=J101 revolute-without-limit::revolute ...

Severities map to `error`, `warning` and `notice`. Data is escaped as GitHub's toolkit does
(`%`, CR and LF); property values also escape `:` and `,`. The macro call chain follows the
message on extra lines (escaped LF), and a plain summary line ends the output.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from robotdesc.diagnostics import Severity
from robotdesc.linting.merge import MergedFinding, merge_findings
from robotdesc.linting.targets import target_name
from robotdesc.report.text import summary_line
from robotdesc.source import Span, passed_sites

if TYPE_CHECKING:
    from robotdesc.linting.result import LintFailure, LintResult

_COMMAND = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}


def escape_data(text: str) -> str:
    """Escape a command's message."""
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def escape_property(text: str) -> str:
    """Escape a command property's value."""
    return escape_data(text).replace(":", "%3A").replace(",", "%2C")


def workflow_command(command: str, message: str, **properties: Any) -> str:
    """`::command key=value,...::message` with escaping; properties that are None or 0 are
    left out."""
    props = ",".join(f"{key}={escape_property(str(value))}"
                     for key, value in properties.items() if value not in (None, 0, ""))
    return f"::{command}{' ' + props if props else ''}::{escape_data(message)}"


def render_github(results: Sequence[LintResult], failures: Sequence[LintFailure] = (), *,
                  cwd: str | None = None) -> str:
    """Annotations for every finding (one per problem and source location, over variants and
    elements) and every file that could not be checked, then a summary line (text ending
    with a newline)."""
    root = os.path.abspath(cwd or os.getcwd())
    lines = [_annotation(finding, root) for finding in merge_findings(results)]
    lines += [_failure(f, root) for f in failures]
    summary = "".join(text for text, _ in summary_line(results, failures))
    if summary:
        lines.append(summary)
    return "".join(line + "\n" for line in lines)


def _annotation(finding: MergedFinding, root: str) -> str:
    diagnostic = finding.diagnostic
    span = diagnostic.where.span if diagnostic.where else None
    stack = diagnostic.where.macro_stack if diagnostic.where else ()
    message = diagnostic.message + finding.variant_note()
    message += "".join(f"\nin macro called from {_location(site, root)}" for site in stack)
    message += "".join(f"\nvalue passed at {_location(site, root)} ({', '.join(names)})"
                       for site, names in passed_sites(diagnostic.where.passed
                                                       if diagnostic.where else ()))
    if len(finding.elements) > 1:
        message += f"\n{finding.elements_text()}"
    if finding.runs > 1 and finding.in_all_variants:
        message += f"\n{finding.variants_text()}"
    return workflow_command(
        _COMMAND[diagnostic.severity], message,
        file=_path(span.path if span else diagnostic.target or finding.target, root),
        line=span.line if span else None, col=span.col if span else None,
        title=f"{diagnostic.code} {diagnostic.name}")


def _failure(failure: LintFailure, root: str) -> str:
    error = failure.error
    span = getattr(error, "span", None)
    message = getattr(error, "message", str(error))
    message += "".join(f"\nin macro called from {_location(site, root)}"
                       for site in getattr(error, "call_stack", ()))
    name = target_name(failure.target, getattr(failure, "variant", ()), root)
    return workflow_command("error", message,
                            file=_path(span.path if span else failure.target, root),
                            line=span.line if span else None, col=span.col if span else None,
                            title=f"robotdesc: {name} could not be checked")


def _path(path: str, root: str) -> str:
    return target_name(path, (), root)


def _location(span: Span, root: str) -> str:
    return str(Span(_path(span.path, root), span.line, span.col))
