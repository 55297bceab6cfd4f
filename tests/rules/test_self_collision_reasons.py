"""K201 and K203 as MoveIt's Setup Assistant sees them: the SRDF reason K203 gives for each
kind of contact by design (fixture: tests/rules/fixtures/kinematics/self_collision.urdf)."""

from __future__ import annotations

from pathlib import Path

import pytest

from robotdesc.model.parse import parse_urdf
from robotdesc.rules.catalog import get_rule
from robotdesc.rules.registry import RuleContext, run_rule

FIXTURE = Path(__file__).parent / "fixtures" / "kinematics" / "self_collision.urdf"
pytest.importorskip("pinocchio")


def findings(code: str) -> list:
    robot = parse_urdf(FIXTURE.read_bytes(), str(FIXTURE))
    rule_ = get_rule(code)
    return list(run_rule(rule_, robot, RuleContext(options=rule_.default_options())))


def test_contact_at_every_configuration_and_at_a_limit_get_their_reasons() -> None:
    always, at_limit = findings("K203")
    assert "every sampled configuration" in always.message
    assert 'link1="left" link2="right" reason="Always"' in always.fix
    assert "joints at a limit" in at_limit.message
    assert 'link1="left2" link2="right2" reason="Default"' in at_limit.fix
    # a one-DOF linkage touching mid-range (Robotiq's knuckles): "Default", not K201
    assert 'link1="knuckle_a" link2="knuckle_b" reason="Default"' in at_limit.fix


def test_only_the_real_overlap_is_a_warning() -> None:
    assert [f.element for f in findings("K201")] == ["link:link7"]
