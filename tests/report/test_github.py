"""GitHub workflow-command annotations: exact snapshot and escaping."""

from __future__ import annotations

import pytest

from robotdesc.report.github import (
    escape_data,
    escape_property,
    render_github,
    workflow_command,
)

from .ci_samples import build_ci_sample


@pytest.fixture
def sample(tmp_path):
    return build_ci_sample(tmp_path)


def test_github_snapshot(sample) -> None:
    results, failures, root = sample
    assert render_github(results, failures, cwd=str(root)).splitlines() == [
        "::error file=arm.xacro,line=3,col=2,title=J101 revolute-without-limit::"
        "revolute joint 'left_elbow' has no <limit>"
        "%0Ain macro called from robot.urdf.xacro:3%0Ain macro called from robot.urdf.xacro:4"
        "%0Ain all 2 variants: [default arguments], [side=left]",
        "::warning file=robot.urdf.xacro,line=5,title=S003 link-name-case-clash::"
        "link 'base' clashes (only in variant [default arguments])",
        "::notice file=robot.urdf.xacro,title=X001 empty-robot::note "
        "(only in variant [default arguments])",
        "::error file=broken.urdf.xacro,line=2,col=3,"
        "title=robotdesc%3A broken.urdf.xacro could not be checked::"
        "undefined property 'undefined'%0Ain macro called from robot.urdf.xacro:9",
        "Found 1 error, 1 warning, 1 info in 2 files. 1 file could not be checked.",
    ]


def test_escaping_follows_the_actions_toolkit() -> None:
    assert escape_data("50% done\r\nnext") == "50%25 done%0D%0Anext"
    assert escape_property("a:b,c%\n") == "a%3Ab%2Cc%25%0A"
    assert workflow_command("warning", "m:1,2", file="x,y.urdf", line=0, title="T") == \
        "::warning file=x%2Cy.urdf,title=T::m:1,2"
