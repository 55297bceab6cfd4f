"""The JUnit report: snapshot, and that a JUnit XML parser (junitparser) reads one suite per
target and one case per rule, with failures carrying the messages."""

from __future__ import annotations

import pytest
from junitparser import Error, Failure, JUnitXml

from robotdesc.diagnostics import Severity
from robotdesc.report.junit import CHECK_CASE, render_junit

from .ci_samples import build_ci_sample, check_snapshot, normalise


@pytest.fixture
def sample(tmp_path):
    return build_ci_sample(tmp_path)


def parse(text: str, tmp_path) -> JUnitXml:
    path = tmp_path / "report.xml"
    path.write_text(text, encoding="utf-8")
    return JUnitXml.fromfile(str(path))


def test_junit_snapshot(sample) -> None:
    results, failures, root = sample
    check_snapshot("sample.junit.xml", normalise(render_junit(results, failures,
                                                              cwd=str(root)), root))


def test_junit_parses_with_a_junit_parser(sample, tmp_path) -> None:
    results, failures, root = sample
    report = parse(render_junit(results, failures, cwd=str(root)), tmp_path)
    suites = {suite.name: suite for suite in report}
    assert list(suites) == ["robot.urdf.xacro", "broken.urdf.xacro"]  # variants together
    main = suites["robot.urdf.xacro"]
    cases = {case.name: case for case in main}
    assert list(cases) == ["J101 revolute-without-limit", "S003 link-name-case-clash",
                           "X001 empty-robot"]
    (failure,) = cases["J101 revolute-without-limit"].result
    assert isinstance(failure, Failure)
    assert failure.message == "revolute joint 'left_elbow' has no <limit>"
    assert "arm.xacro:3:2: J101 [error]" in failure.text
    assert "in macro called from robot.urdf.xacro:4" in failure.text
    assert main.tests == 3 and main.failures == 3 and main.errors == 0
    (error,) = next(iter(suites["broken.urdf.xacro"])).result
    assert isinstance(error, Error) and "undefined property" in error.message
    assert report.tests == 4 and report.failures == 3 and report.errors == 1


def test_findings_below_fail_on_pass_and_go_to_system_out(sample, tmp_path) -> None:
    results, _, root = sample
    report = parse(render_junit(results, fail_on=Severity.ERROR, cwd=str(root)), tmp_path)
    cases = {case.name: case for case in next(iter(report))}
    assert cases["S003 link-name-case-clash"].is_passed
    assert "S003 [warning] link 'base' clashes" in cases["S003 link-name-case-clash"].system_out
    assert not cases["J101 revolute-without-limit"].is_passed


def test_failure_case_name(sample, tmp_path) -> None:
    _, failures, root = sample
    report = parse(render_junit([], failures, cwd=str(root)), tmp_path)
    assert [case.name for suite in report for case in suite] == [CHECK_CASE]
