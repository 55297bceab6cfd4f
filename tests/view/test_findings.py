"""Findings attached to links."""

from __future__ import annotations

from robotdesc.diagnostics import Diagnostic, Severity
from robotdesc.model.elements import Joint, Link, Robot
from robotdesc.view.findings import findings_by_link, link_of

ROBOT = Robot("r", (Link("base"), Link("arm"), Link("arm/tool")),
              (Joint("shoulder", "revolute", "base", "arm"),
               Joint("ghost", "fixed", "base", "nowhere")))


def test_link_of_each_element_kind() -> None:
    assert link_of("link:arm", ROBOT) == "arm"
    assert link_of("link:arm/inertial", ROBOT) == "arm"
    assert link_of("link:arm/tool/visual[0]", ROBOT) == "arm/tool"  # the longest name wins
    assert link_of("joint:shoulder", ROBOT) == "arm"
    assert link_of("gazebo:base", ROBOT) == "base"
    assert link_of("joint:ghost", ROBOT) is None
    assert link_of("link:elsewhere", ROBOT) is None
    assert link_of("robot:r", ROBOT) is None and link_of("", ROBOT) is None


def _diagnostic(element: str) -> Diagnostic:
    return Diagnostic("X1", "x", Severity.WARNING, "m", None, element)


def test_grouping_keeps_document_order_and_the_rest() -> None:
    per_link, others = findings_by_link(ROBOT, [_diagnostic("joint:shoulder"),
                                                _diagnostic("transmission:t"),
                                                _diagnostic("link:base/inertial")])
    assert list(per_link) == ["base", "arm"]
    assert [d.element for d in others] == ["transmission:t"]
