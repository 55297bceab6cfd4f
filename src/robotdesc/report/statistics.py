"""`lint --statistics`: how many findings each rule made, most first (a first look at a
legacy package before choosing what to fix, ignore or baseline).

    count  code  name                      severity
       12  J101  revolute-without-limit    error
        3  S003  link-name-case-clash      warning
"""

from __future__ import annotations

import json
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from robotdesc.linting.merge import merge_findings
from robotdesc.report.table import render_table

if TYPE_CHECKING:
    from robotdesc.diagnostics import Severity
    from robotdesc.linting.result import LintResult


@dataclass(frozen=True)
class CodeCount:
    """The findings of one rule.

    Attributes:
        code: the rule code.
        name: the rule name.
        severity: the worst severity among its findings.
        count: how many findings.
    """

    code: str
    name: str
    severity: str
    count: int


def code_counts(results: Sequence[LintResult]) -> list[CodeCount]:
    """Findings counted per rule code, most first, then by code (a problem repeated over
    variants and elements counts once, as in the reports)."""
    counts: Counter[str] = Counter()
    names: dict[str, str] = {}
    worst: dict[str, Severity] = {}
    for finding in merge_findings(results):
        d = finding.diagnostic
        counts[d.code] += 1
        names[d.code] = d.name
        worst[d.code] = max(worst.get(d.code, d.severity), d.severity)
    return [CodeCount(code, names[code], str(worst[code]), n)
            for code, n in sorted(counts.items(), key=lambda item: (-item[1], item[0]))]


def render_statistics_text(results: Sequence[LintResult]) -> str:
    """The counts as an aligned table (text ending with a newline)."""
    rows = [(str(c.count), c.code, c.name, c.severity) for c in code_counts(results)]
    if not rows:
        return "No findings.\n"
    total = sum(int(row[0]) for row in rows)
    width = max(len(row[0]) for row in rows + [("count", "", "", ""), (str(total), "", "", "")])
    text = render_table(("count", "code", "name", "severity"), rows, right=(0,), wrap=2)
    return text + f"{str(total).rjust(width)}  total\n"


def render_statistics_json(results: Sequence[LintResult]) -> str:
    """The counts as a JSON array of {code, name, severity, count}."""
    document = [{"code": c.code, "name": c.name, "severity": c.severity, "count": c.count}
                for c in code_counts(results)]
    return json.dumps(document, indent=2) + "\n"
