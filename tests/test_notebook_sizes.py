"""What the public API returns shows small in a notebook (issue 34): on the Engineer, every
result's repr is under 2 KB and its HTML (as Jupyter draws it) under 200 KB."""

from __future__ import annotations

from pathlib import Path

import pytest

import robotdesc
from robotdesc.report.notebook import html_of

ENGINEER = str(Path(__file__).resolve().parents[1] / "robots" / "engineer_description" / "urdf"
               / "engineer.urdf.xacro")
REPR_LIMIT, HTML_LIMIT = 2_000, 200_000


def _check(value: object) -> None:
    assert len(repr(value)) < REPR_LIMIT, repr(value)[:300]
    drawn = getattr(value, "_repr_html_", None)
    page = drawn() if drawn is not None else html_of(value)
    assert page is None or len(page) < HTML_LIMIT, (type(value).__name__, len(page))


@pytest.mark.slow
def test_every_public_result_is_small_in_a_notebook() -> None:
    robot = robotdesc.load(ENGINEER)
    result = robotdesc.lint(ENGINEER)
    for value in (robot, robotdesc.expand(ENGINEER), result, robotdesc.mesh_inertia(ENGINEER),
                  robotdesc.show(result),
                  robotdesc.generate_collision(robot, "hull", links=["head_link"], jobs=1)):
        _check(value)
