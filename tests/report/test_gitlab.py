"""GitLab Code Quality report: snapshot and the fields GitLab requires."""

from __future__ import annotations

import json

import pytest

from robotdesc.report.gitlab import INPUT_ERROR_CHECK, render_gitlab

from .ci_samples import build_ci_sample, check_snapshot, normalise


@pytest.fixture
def sample(tmp_path):
    return build_ci_sample(tmp_path)


def test_gitlab_snapshot(sample) -> None:
    results, failures, root = sample
    check_snapshot("sample.gitlab.json", normalise(render_gitlab(results, failures,
                                                                 cwd=str(root)), root))


def test_every_issue_has_the_required_fields_and_a_unique_fingerprint(sample) -> None:
    results, failures, root = sample
    issues = json.loads(render_gitlab(results, failures, cwd=str(root)))
    assert len(issues) == 4  # the variant's finding is the first one's
    for issue in issues:
        assert set(issue) == {"description", "check_name", "fingerprint", "severity",
                              "location"}
        assert issue["severity"] in {"info", "minor", "major", "critical", "blocker"}
        assert issue["location"]["lines"]["begin"] >= 1
    assert len({issue["fingerprint"] for issue in issues}) == 4
    assert issues[0]["location"] == {"path": "arm.xacro", "lines": {"begin": 3}}
    assert issues[-1]["check_name"] == INPUT_ERROR_CHECK
