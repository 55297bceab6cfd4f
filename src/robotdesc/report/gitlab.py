"""GitLab Code Quality report (the Code Climate JSON subset GitLab reads).

A JSON array with one issue per finding (a problem repeated over variants and elements is one
issue, see robotdesc.linting.merge): `description`, `check_name`, a line-free
`fingerprint`, `severity` (error -> major, warning -> minor, info -> info) and `location`
(path relative to the working directory, begin line). Files that could not be checked are
`blocker` issues with check_name "robotdesc-input-error".
"""

from __future__ import annotations

import hashlib
import json
import os
from collections import Counter
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from robotdesc.diagnostics import Severity
from robotdesc.linting.merge import merge_findings, message_key
from robotdesc.linting.targets import target_name

if TYPE_CHECKING:
    from robotdesc.linting.result import LintFailure, LintResult

_SEVERITY = {Severity.ERROR: "major", Severity.WARNING: "minor", Severity.INFO: "info"}
INPUT_ERROR_CHECK = "robotdesc-input-error"


def render_gitlab(results: Sequence[LintResult], failures: Sequence[LintFailure] = (), *,
                  cwd: str | None = None) -> str:
    """The Code Quality report as JSON text ending with a newline."""
    root = os.path.abspath(cwd or os.getcwd())
    issues: list[dict[str, Any]] = []
    seen: Counter[tuple[str, ...]] = Counter()  # identical findings get distinct fingerprints
    for finding in merge_findings(results):  # one issue per problem and source location
        d = finding.diagnostic
        target = target_name(finding.target, (), root)
        span = d.where.span if d.where else None
        elements = f" ({finding.elements_text()})" if len(finding.elements) > 1 else ""
        issues.append(_issue(f"{d.code} {d.name}: {d.message}{finding.variant_note()}{elements}",
                             d.code, _SEVERITY[d.severity],
                             target_name(span.path if span else finding.target, (), root),
                             span.line if span else 0,
                             _occurrence(seen, target, d.code, *sorted(finding.elements),
                                         message_key(d))))
    for failure in failures:
        error = failure.error
        span = getattr(error, "span", None)
        target = target_name(failure.target, getattr(failure, "variant", ()), root)
        message = getattr(error, "message", str(error))
        issues.append(_issue(f"{target} could not be checked: {message}", INPUT_ERROR_CHECK,
                             "blocker", target_name(span.path if span else failure.target, (),
                                                    root),
                             span.line if span else 0, _occurrence(seen, target, message)))
    return json.dumps(issues, indent=2, ensure_ascii=False) + "\n"


def _occurrence(seen: Counter[tuple[str, ...]], *identity: str) -> tuple[str, ...]:
    seen[identity] += 1
    return (*identity, str(seen[identity]))


def _issue(description: str, check: str, severity: str, path: str, line: int,
           identity: tuple[str, ...]) -> dict[str, Any]:
    fingerprint = hashlib.sha256("\0".join(identity).encode("utf-8")).hexdigest()[:32]
    return {"description": description, "check_name": check, "fingerprint": fingerprint,
            "severity": severity, "location": {"path": path, "lines": {"begin": line or 1}}}
