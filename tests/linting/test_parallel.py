"""Linting targets across worker processes gives the same outcomes, in target order."""

from __future__ import annotations

from pathlib import Path

import pytest

from robotdesc.linting.parallel import effective_jobs, lint_targets
from robotdesc.linting.result import LintFailure
from robotdesc.linting.targets import LintTarget, discover_targets

WORKSPACE = Path(__file__).resolve().parents[1] / "fixtures" / "ci_workspace"


def summary(outcomes) -> list:
    return [(type(o).__name__, o.target, o.variant,
             [(d.code, d.element, d.where.span.line) for d in getattr(o, "diagnostics", ())])
            for o in outcomes]


def test_two_jobs_match_one_job(tmp_path) -> None:
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot name='b'><link name='a'></robot>")
    targets = [*discover_targets(str(WORKSPACE)).targets, LintTarget(str(broken))]
    one = lint_targets(targets, jobs=1)
    two = lint_targets(targets, jobs=2)
    assert summary(one) == summary(two)
    assert isinstance(two[-1], LintFailure) and two[-1].error.span.line == 1
    long = two[1]
    assert long.variant == (("arm_type", "long"),) and long.expanded is None
    assert [(d.code, d.element) for d in long.diagnostics] == [("J102", "joint:arm_elbow")]
    assert two[0].diagnostics == ()  # the short arm has no elbow


def test_jobs_zero_means_one_per_cpu() -> None:
    assert effective_jobs(0) >= 1 and effective_jobs(3) == 3
    with pytest.raises(ValueError):
        effective_jobs(-1)
