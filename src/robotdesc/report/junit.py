"""JUnit XML report, as CI systems (GitLab, Jenkins, Azure, CircleCI) render test results.

One `<testsuite>` per target (its variants together: a problem repeated over variants and
elements is one finding naming them, see robotdesc.linting.merge) and one `<testcase>` per
rule that ran on it. A rule with findings at or above `fail_on` fails, its `<failure>`
carrying every finding (location, message, macro call chain); findings below `fail_on` are
listed in the test case's `<system-out>`. A target that could not be checked is a suite with
one errored test case.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import TYPE_CHECKING

from lxml import etree

from robotdesc.diagnostics import Severity
from robotdesc.linting.merge import MergedFinding, merge_findings
from robotdesc.linting.targets import target_name
from robotdesc.source import Span, passed_sites

if TYPE_CHECKING:
    from robotdesc.linting.result import LintFailure, LintResult

#: The name of the test case of a target that could not be checked.
CHECK_CASE = "expand and parse"


def render_junit(results: Sequence[LintResult], failures: Sequence[LintFailure] = (), *,
                 fail_on: Severity = Severity.INFO, cwd: str | None = None) -> str:
    """The JUnit XML document (UTF-8 text with an XML declaration, ending with a newline).

    Args:
        results: `LintResult`s.
        failures: `LintFailure`s.
        fail_on: the lowest severity that fails a test case.
        cwd: the directory paths are shown relative to (default: the working directory).
    """
    root_dir = os.path.abspath(cwd or os.getcwd())
    suites = etree.Element("testsuites", name="robotdesc")
    by_target: dict[str, list[LintResult]] = {}
    for result in results:
        by_target.setdefault(result.target, []).append(result)
    merged = merge_findings(results)
    for target, runs in by_target.items():
        suites.append(_result_suite(target, runs, [f for f in merged if f.target == target],
                                    fail_on, root_dir))
    for failure in failures:
        suites.append(_failure_suite(failure, root_dir))
    for key in ("tests", "failures", "errors", "skipped"):
        suites.set(key, str(sum(int(s.get(key)) for s in suites)))
    suites.set("time", "0")
    text: str = etree.tostring(suites, pretty_print=True, encoding="unicode")
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + text


def _result_suite(target: str, runs: Sequence[LintResult], findings: Sequence[MergedFinding],
                  fail_on: Severity, root: str) -> etree._Element:
    name = target_name(target, getattr(runs[0], "variant", ()) if len(runs) == 1 else (),
                       root)
    by_code: dict[str, list[MergedFinding]] = {}
    for finding in findings:
        by_code.setdefault(finding.diagnostic.code, []).append(finding)
    codes = list(dict.fromkeys([*(c for r in runs for c in r.rules_run), *by_code]))
    suite = _suite(name, target, root)
    failed = 0
    names = {f.diagnostic.code: f.diagnostic.name for f in findings}
    for code in codes:
        found = by_code.get(code, [])
        case = etree.SubElement(suite, "testcase", name=_case_name(code, names),
                                classname=name, file=_shown(target, root), time="0")
        failing = [f for f in found if f.diagnostic.severity >= fail_on]
        passing = [f for f in found if f.diagnostic.severity < fail_on]
        if failing:
            failed += 1
            first = failing[0].diagnostic
            more = f" (and {len(failing) - 1} more)" if len(failing) > 1 else ""
            span = first.where.span if first.where else None
            if span and span.line:  # where the first failing finding is written
                case.set("file", _shown(span.path, root))
                case.set("line", str(span.line))
            failure = etree.SubElement(case, "failure",
                                       message=first.message + failing[0].variant_note() + more,
                                       type=str(max(f.diagnostic.severity for f in failing)))
            failure.text = "\n".join(_finding_text(d, root) for d in failing)
        if passing:
            out = etree.SubElement(case, "system-out")
            out.text = "\n".join(_finding_text(d, root) for d in passing)
    _count(suite, tests=len(codes), failures=failed, errors=0)
    return suite


def _failure_suite(failure: LintFailure, root: str) -> etree._Element:
    name = target_name(failure.target, getattr(failure, "variant", ()), root)
    error = failure.error
    message = getattr(error, "message", str(error))
    suite = _suite(name, failure.target, root)
    case = etree.SubElement(suite, "testcase", name=CHECK_CASE, classname=name,
                            file=_shown(failure.target, root), time="0")
    element = etree.SubElement(case, "error", message=message, type=type(error).__name__)
    span = getattr(error, "span", None)
    lines = [f"{_location(span, failure.target, root)}: error: {message}"]
    lines += [f"  in macro called from {_location(s, s.path, root)}"
              for s in getattr(error, "call_stack", ())]
    element.text = "\n".join(lines)
    _count(suite, tests=1, failures=0, errors=1)
    return suite


def _suite(name: str, target: str, root: str) -> etree._Element:
    suite = etree.Element("testsuite", name=name, time="0")
    properties = etree.SubElement(suite, "properties")
    etree.SubElement(properties, "property", name="file", value=_shown(target, root))
    return suite


def _count(suite: etree._Element, *, tests: int, failures: int, errors: int) -> None:
    for key, value in (("tests", tests), ("failures", failures), ("errors", errors),
                       ("skipped", 0)):
        suite.set(key, str(value))


def _case_name(code: str, names: dict[str, str]) -> str:
    if code in names:
        return f"{code} {names[code]}"
    from robotdesc.rules.catalog import get_rule

    rule = get_rule(code)
    return f"{code} {rule.name}" if rule else code


def _finding_text(finding: MergedFinding, root: str) -> str:
    diagnostic = finding.diagnostic
    span = diagnostic.where.span if diagnostic.where else None
    stack = diagnostic.where.macro_stack if diagnostic.where else ()
    lines = [(f"{_location(span, diagnostic.target, root)}: {diagnostic.code} "
              f"[{diagnostic.severity}] {diagnostic.message}{finding.variant_note()}")]
    lines += [f"  in macro called from {_location(site, site.path, root)}" for site in stack]
    lines += [f"  value passed at {_location(site, site.path, root)} ({', '.join(names)})"
              for site, names in passed_sites(diagnostic.where.passed if diagnostic.where else ())]
    if len(finding.elements) > 1:
        lines.append(f"  {finding.elements_text()}")
    if finding.runs > 1 and finding.in_all_variants:
        lines.append(f"  {finding.variants_text()}")
    return "\n".join(lines)


def _location(span: Span | None, fallback: str, root: str) -> str:
    if span is None:
        return _shown(fallback, root)
    return str(Span(_shown(span.path, root), span.line, span.col))


def _shown(path: str, root: str) -> str:
    return target_name(path, (), root)
