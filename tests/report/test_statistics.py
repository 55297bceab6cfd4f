"""`lint --statistics`: counts per rule code."""

from __future__ import annotations

import dataclasses
import json

from robotdesc.report.statistics import (
    code_counts,
    render_statistics_json,
    render_statistics_text,
)

from robotdesc.source import Span

from .ci_samples import build_ci_sample


def _elsewhere(diagnostic):
    """The diagnostic one line further down (another problem, not the same one again)."""
    span = diagnostic.where.span
    where = dataclasses.replace(diagnostic.where, span=Span(span.path, span.line + 1, span.col))
    return dataclasses.replace(diagnostic, where=where)


def test_counts_per_code_most_first(tmp_path) -> None:
    results, _, _ = build_ci_sample(tmp_path)
    results[1] = dataclasses.replace(results[1], diagnostics=tuple(
        _elsewhere(d) for d in results[1].diagnostics))
    assert [(c.code, c.count, c.severity) for c in code_counts(results)] == [
        ("J101", 2, "error"), ("S003", 1, "warning"), ("X001", 1, "info")]
    assert render_statistics_text(results) == (
        "count  code  name                    severity\n"
        "    2  J101  revolute-without-limit  error\n"
        "    1  S003  link-name-case-clash    warning\n"
        "    1  X001  empty-robot             info\n"
        "    4  total\n")
    assert json.loads(render_statistics_json(results))[0] == {
        "code": "J101", "name": "revolute-without-limit", "severity": "error", "count": 2}


def test_a_problem_repeated_over_variants_counts_once(tmp_path) -> None:
    results, _, _ = build_ci_sample(tmp_path)
    assert [(c.code, c.count) for c in code_counts(results)] == [
        ("J101", 1), ("S003", 1), ("X001", 1)]


def test_no_findings() -> None:
    assert render_statistics_text([]) == "No findings.\n"
