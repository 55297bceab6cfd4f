"""Machine-readable report: a stable, versioned JSON document (see docs/json-format.md).

The shape only grows within a schema version: new keys may be added, none are renamed or
removed without bumping `schema_version`.
"""

from __future__ import annotations

import json
import os
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from robotdesc._version import __version__
from robotdesc.diagnostics import Diagnostic, Severity
from robotdesc.linting.merge import merge_findings
from robotdesc.rules.fixes import fix_applicability
from robotdesc.source import Span, passed_sites

if TYPE_CHECKING:
    from robotdesc.linting.result import LintFailure, LintResult

SCHEMA_VERSION = 1

_SPAN = {"type": "object", "required": ["file", "line"], "additionalProperties": False,
         "properties": {"file": {"type": "string"},
                        "line": {"type": ["integer", "null"], "minimum": 1}}}
_PASSED = {"type": "object", "required": ["file", "line", "values"], "additionalProperties": False,
           "properties": {"file": {"type": "string"},
                          "line": {"type": ["integer", "null"], "minimum": 1},
                          "values": {"type": "array", "items": {"type": "string"}}}}
_POSITION = {"file": {"type": ["string", "null"]},
             "line": {"type": ["integer", "null"], "minimum": 1},
             "column": {"type": ["integer", "null"], "minimum": 1},
             "macro_stack": {"type": "array", "items": _SPAN},
             "target": {"type": "string"},
             "variant": {"type": "object", "additionalProperties": {"type": "string"}}}

#: JSON Schema (draft 2020-12) of the report; tests validate the output against it.
JSON_SCHEMA: dict[str, Any] = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "title": "robotdesc lint report",
    "type": "object",
    "required": ["schema_version", "tool", "summary", "diagnostics", "failures"],
    "properties": {
        "schema_version": {"const": SCHEMA_VERSION},
        "tool": {"type": "object", "required": ["name", "version"],
                 "properties": {"name": {"const": "robotdesc"}, "version": {"type": "string"}}},
        "summary": {
            "type": "object",
            "required": ["files_checked", "files_not_checked", "error", "warning", "info"],
            "properties": {
                **{key: {"type": "integer", "minimum": 0} for key in
                   ("files_checked", "files_not_checked", "error", "warning", "info",
                    "suppressed", "files_read")},
                "suppressed_by": {"type": "object", "additionalProperties": False,
                                  "properties": {key: {"type": "integer", "minimum": 0}
                                                 for key in ("inline", "config", "baseline")}},
                "variants": {"type": "array", "items": {
                    "type": "object", "required": ["target", "args", "variant"],
                    "properties": {
                        "target": {"type": "string"},
                        "args": {"type": "object", "additionalProperties": {"type": "string"}},
                        "variant": {"type": "object",
                                    "additionalProperties": {"type": "string"}}}}},
            },
        },
        "diagnostics": {"type": "array", "items": {
            "type": "object",
            "required": ["code", "name", "severity", "message", "file", "line", "column",
                         "element", "macro_stack", "fix", "target"],
            "properties": {"code": {"type": "string", "pattern": "^[A-Z]+[0-9]{3}$"},
                           "name": {"type": "string"},
                           "severity": {"enum": ["error", "warning", "info"]},
                           "message": {"type": "string"},
                           "element": {"type": "string"},
                           "fix": {"type": ["string", "null"]},
                           "fix_applicability": {"enum": ["safe", "unsafe", None]},
                           "passed_values": {"type": "array", "items": _PASSED},
                           "elements": {"type": "array", "items": {"type": "string"}},
                           "variants": {"type": "array", "items": {
                               "type": "object", "required": ["args", "variant"],
                               "properties": {
                                   "args": {"type": "object",
                                            "additionalProperties": {"type": "string"}},
                                   "variant": {"type": "object",
                                               "additionalProperties": {"type": "string"}}}}},
                           "in_all_variants": {"type": "boolean"},
                           **_POSITION},
        }},
        "failures": {"type": "array", "items": {
            "type": "object",
            "required": ["kind", "message", "file", "line", "column", "macro_stack", "target"],
            "properties": {"kind": {"type": "string"}, "message": {"type": "string"},
                           **_POSITION},
        }},
    },
}


def diagnostic_dict(diagnostic: Diagnostic) -> dict[str, Any]:
    """One diagnostic as a JSON-ready dict (unknown line/column are null)."""
    span = diagnostic.where.span if diagnostic.where else None
    stack = diagnostic.where.macro_stack if diagnostic.where else ()
    return {
        "code": diagnostic.code,
        "name": diagnostic.name,
        "severity": str(diagnostic.severity),
        "message": diagnostic.message,
        **_position(span),
        "element": diagnostic.element,
        "macro_stack": [_span_dict(site) for site in stack],
        "passed_values": [{**_span_dict(site), "values": list(names)} for site, names
                          in passed_sites(diagnostic.where.passed if diagnostic.where else ())],
        "fix": diagnostic.fix,
        "fix_applicability": _applicability(diagnostic),
        "target": diagnostic.target,
    }


def _applicability(diagnostic: Diagnostic) -> str | None:
    """"safe" or "unsafe" when `robotdesc lint --fix` can write the finding's fix, else None."""
    found = fix_applicability(diagnostic.code, diagnostic.fix)
    return found.value if found is not None else None


def failure_dict(failure: LintFailure) -> dict[str, Any]:
    """A file that could not be checked (`LintFailure`) as a JSON-ready dict."""
    error = failure.error
    return {
        "kind": type(error).__name__,
        "message": getattr(error, "message", str(error)),
        **_position(getattr(error, "span", None)),
        "macro_stack": [_span_dict(site) for site in getattr(error, "call_stack", ())],
        "target": os.path.abspath(failure.target),
    }


def report_dict(results: Sequence[LintResult], failures: Sequence[LintFailure] = ()
                ) -> dict[str, Any]:
    """The whole report for `LintResult`s and `LintFailure`s: one diagnostic per problem
    and source location (merged over variants and elements, robotdesc.linting.merge)."""

    merged = merge_findings(results)
    diagnostics = [finding.diagnostic for finding in merged]
    summary: dict[str, object] = {"files_checked": len(results),
                                  "files_not_checked": len(failures)}
    summary.update({str(level): sum(d.severity == level for d in diagnostics)
                    for level in sorted(Severity, reverse=True)})
    suppressed: int = sum(getattr(result, "suppressed", 0) for result in results)
    summary["suppressed"] = suppressed
    summary["suppressed_by"] = {
        "inline": suppressed,
        "config": sum(getattr(result, "suppressed_by_config", 0) for result in results),
        "baseline": sum(getattr(result, "suppressed_by_baseline", 0) for result in results)}
    summary["files_read"] = len(set().union(*(getattr(result, "files_read", frozenset())
                                              for result in results)))
    summary["variants"] = [{"target": result.target,
                            "args": dict(getattr(result, "args", ())),
                            "variant": dict(getattr(result, "variant", ()))}
                           for result in results]
    return {
        "schema_version": SCHEMA_VERSION,
        "tool": {"name": "robotdesc", "version": __version__},
        "summary": summary,
        "diagnostics": [{**diagnostic_dict(finding.diagnostic),
                         "variant": dict(finding.variant_matrix[0]),
                         "elements": list(finding.elements),
                         "variants": [{"args": dict(args), "variant": dict(matrix)}
                                      for args, matrix in zip(finding.variants,
                                                              finding.variant_matrix)],
                         "in_all_variants": finding.in_all_variants}
                        for finding in merged],
        "failures": [{**failure_dict(f), "variant": dict(getattr(f, "variant", ()))}
                     for f in failures],
    }


def render_json(results: Sequence[LintResult], failures: Sequence[LintFailure] = ()) -> str:
    """The report as indented JSON text, ending with a newline."""
    return json.dumps(report_dict(results, failures), indent=2, ensure_ascii=False) + "\n"


def _position(span: Span | None) -> dict[str, Any]:
    return {"file": os.path.abspath(span.path) if span else None,
            "line": (span.line or None) if span else None,
            "column": (span.col or None) if span else None}


def _span_dict(span: Span) -> dict[str, Any]:
    return {"file": os.path.abspath(span.path), "line": span.line or None}
