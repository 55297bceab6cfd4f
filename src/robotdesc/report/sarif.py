"""SARIF 2.1.0 report, for GitHub code scanning and other SARIF viewers.

One run; one result per problem and source location (a finding repeated over variants and
elements is one result listing them in its properties, see robotdesc.linting.merge). The
driver lists every rule with its name, documentation and a help URI into
docs/rules.md. A result points at the xacro source line of the element; inside a macro the
call sites follow as related locations (innermost first), linked from the message. Paths
below the working directory are relative to `%SRCROOT%`, which `originalUriBaseIds` maps to
the working directory. Files that could not be checked become error notifications of the
invocation (and `executionSuccessful` is false).
"""

from __future__ import annotations

import hashlib
import json
import os
import urllib.parse
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from robotdesc._version import __version__
from robotdesc.diagnostics import Diagnostic, Severity
from robotdesc.linting.merge import MergedFinding, merge_findings, message_key, run_label
from robotdesc.linting.targets import target_name
from robotdesc.source import Span, passed_sites

if TYPE_CHECKING:
    from robotdesc.linting.result import LintFailure, LintResult
    from robotdesc.rules.registry import Rule

SARIF_VERSION = "2.1.0"
SARIF_SCHEMA_URI = "https://json.schemastore.org/sarif-2.1.0.json"
INFORMATION_URI = "https://github.com/robotdesc/robotdesc"
RULES_DOC_URI = "https://github.com/robotdesc/robotdesc/blob/main/docs/rules.md"
SRCROOT = "%SRCROOT%"
FINGERPRINT_KEY = "robotdescFinding/v2"

_LEVEL = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}


def render_sarif(results: Sequence[LintResult], failures: Sequence[LintFailure] = (), *,
                 rules: Sequence[Rule] | None = None, cwd: str | None = None) -> str:
    """The SARIF log as indented JSON text, ending with a newline.

    Args:
        results: `LintResult`s.
        failures: `LintFailure`s (files that could not be checked).
        rules: the rule descriptors to list (default: every registered rule).
        cwd: the source root relative paths are written against (default: working dir).
    """
    return json.dumps(sarif_log(results, failures, rules=rules, cwd=cwd), indent=2,
                      ensure_ascii=False) + "\n"


def sarif_log(results: Sequence[LintResult], failures: Sequence[LintFailure] = (), *,
              rules: Sequence[Rule] | None = None, cwd: str | None = None) -> dict[str, Any]:
    """The SARIF log as a JSON-ready dict."""

    if rules is None:
        from robotdesc.rules.catalog import all_rules

        rules = all_rules()
    root = os.path.abspath(cwd or os.getcwd())
    index = {rule.code: i for i, rule in enumerate(rules)}
    driver = {"name": "robotdesc", "version": __version__, "semanticVersion": __version__,
              "informationUri": INFORMATION_URI,
              "rules": [rule_descriptor(rule) for rule in rules]}
    return {
        "$schema": SARIF_SCHEMA_URI,
        "version": SARIF_VERSION,
        "runs": [{
            "tool": {"driver": driver},
            "invocations": [{
                "executionSuccessful": not failures,
                "toolExecutionNotifications": [_notification(f, root) for f in failures],
            }],
            "originalUriBaseIds": {SRCROOT: {"uri": Path(root).as_uri().rstrip("/") + "/"}},
            "columnKind": "unicodeCodePoints",
            "results": [_result(finding, index, root) for finding in merge_findings(results)],
        }],
    }


def rule_descriptor(rule: Rule) -> dict[str, Any]:
    """A rule's SARIF reportingDescriptor: id, name, descriptions, help, default level."""
    from robotdesc.rules.docs import SECTION_HEADINGS, rule_anchor

    doc = rule.doc or rule.summary
    what = doc.split(f"\n{SECTION_HEADINGS[0]}", 1)[0].strip()
    markdown = "\n".join(f"**{line.strip()}**" if line.strip() in SECTION_HEADINGS else line
                         for line in doc.splitlines())
    return {
        "id": rule.code,
        "name": rule.name,
        "shortDescription": {"text": rule.summary},
        "fullDescription": {"text": what},
        "help": {"text": doc, "markdown": markdown},
        "helpUri": f"{RULES_DOC_URI}#{rule_anchor(rule)}",
        "defaultConfiguration": {"level": _LEVEL[rule.severity]},
        "properties": {"tags": [rule.family], "family": rule.family},
    }


def artifact_location(path: str, root: str) -> dict[str, str]:
    """A file as a SARIF artifactLocation: relative to `%SRCROOT%` when below `root`, else an
    absolute file URI."""
    absolute = os.path.abspath(path)
    relative = os.path.relpath(absolute, root) if absolute.startswith(root + os.sep) else None
    if relative is None:
        return {"uri": Path(absolute).as_uri()}
    return {"uri": urllib.parse.quote(relative.replace(os.sep, "/")), "uriBaseId": SRCROOT}


def fingerprint(diagnostic: Diagnostic, target: str, elements: Sequence[str] = ()) -> str:
    """A line-free identity of a finding: its target (without variant), code, elements and
    message (the element's name aside), the same whichever variants it occurs in."""
    names = "\0".join(sorted(elements or [diagnostic.element]))
    material = f"{target}\0{diagnostic.code}\0{names}\0{message_key(diagnostic)}"
    return hashlib.sha256(material.encode("utf-8")).hexdigest()[:32]


def _physical(span: Span | None, fallback: str, root: str) -> dict[str, Any]:
    location: dict[str, Any] = {"artifactLocation": artifact_location(
        span.path if span else fallback, root)}
    if span and span.line:
        region: dict[str, int] = {"startLine": span.line}
        if span.col:
            region["startColumn"] = span.col
        location["region"] = region
    return location


def _result(finding: MergedFinding, index: dict[str, int], root: str) -> dict[str, Any]:
    diagnostic = finding.diagnostic
    span = diagnostic.where.span if diagnostic.where else None
    stack = diagnostic.where.macro_stack if diagnostic.where else ()
    target = target_name(finding.target, (), root)
    location: dict[str, Any] = {"physicalLocation": _physical(span, finding.target, root)}
    if finding.elements:
        location["logicalLocations"] = [{"fullyQualifiedName": element,
                                         "name": element.split(":", 1)[-1],
                                         "kind": "element"} for element in finding.elements]
    message = diagnostic.message + finding.variant_note()
    related = []
    for number, site in enumerate(stack, 1):
        related.append({"id": number, "physicalLocation": _physical(site, site.path, root),
                        "message": {"text": f"macro call {number} of {len(stack)} "
                                            "(innermost first)"}})
    sites = passed_sites(diagnostic.where.passed if diagnostic.where else ())
    for number, (site, names) in enumerate(sites, len(related) + 1):
        related.append({"id": number, "physicalLocation": _physical(site, site.path, root),
                        "message": {"text": f"value passed at this call ({', '.join(names)})"}})
    if related:  # the message links its related locations: escape brackets of its own
        message = message.replace("[", "\\[").replace("]", "\\]")
        if stack:
            links = " <- ".join(f"[{_short(site)}]({number})"
                                for number, site in enumerate(stack, 1))
            message += f" (in a macro called from {links})"
        if sites:
            links = ", ".join(f"[{_short(site)}]({number})"
                              for number, (site, _) in enumerate(sites, len(stack) + 1))
            message += f" (value passed at {links})"
    entry: dict[str, Any] = {
        "ruleId": diagnostic.code,
        "level": _LEVEL[diagnostic.severity],
        "message": {"text": message},
        "locations": [location],
        "partialFingerprints": {FINGERPRINT_KEY: fingerprint(diagnostic, target,
                                                             finding.elements)},
        "properties": {"target": target, "element": diagnostic.element,
                       "elements": list(finding.elements),
                       "variants": [run_label(args, matrix) for args, matrix
                                    in zip(finding.variants, finding.variant_matrix)],
                       "inAllVariants": finding.in_all_variants},
    }
    if diagnostic.code in index:
        entry["ruleIndex"] = index[diagnostic.code]
    if related:
        entry["relatedLocations"] = related
    if diagnostic.fix:
        entry["properties"]["fix"] = diagnostic.fix
    return entry


def _notification(failure: LintFailure, root: str) -> dict[str, Any]:
    error = failure.error
    span = getattr(error, "span", None)
    target = target_name(failure.target, getattr(failure, "variant", ()), root)
    return {"level": "error",
            "message": {"text": f"{target}: could not be checked: "
                                f"{getattr(error, 'message', str(error))}"},
            "locations": [{"physicalLocation": _physical(span, failure.target, root)}],
            "properties": {"kind": type(error).__name__, "target": target}}


def _short(span: Span) -> str:
    return f"{os.path.basename(span.path)}:{span.line}" if span.line else \
        os.path.basename(span.path)
