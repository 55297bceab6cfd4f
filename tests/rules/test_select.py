"""Rule selection by specificity: codes, prefixes, names, ALL; ignore wins ties."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from robotdesc.rules.select import find_rule, is_selected, select_rules, unknown_selectors

RULES = [SimpleNamespace(code=c, name=n, opt_in=False) for c, n in [
    ("J101", "revolute-without-limit"), ("J201", "mimic-target-missing"),
    ("S001", "no-root-link"), ("RD001", "unused-suppression")]]


def codes(select, ignore=()):
    return [r.code for r in select_rules(RULES, select, ignore)]


@pytest.mark.parametrize("select, ignore, expected", [
    (None, (), ["J101", "J201", "S001", "RD001"]),
    (["ALL"], ["J"], ["S001", "RD001"]),
    (["J"], ["J1"], ["J201"]),
    (["J101"], ["J"], ["J101"]),
    (["j1"], (), ["J101"]),
    (["no-root-link"], (), ["S001"]),
    (["J"], ["revolute-without-limit"], ["J201"]),
    (["J"], ["J"], []),
    ([], (), []),
])
def test_select_rules(select, ignore, expected) -> None:
    assert codes(select, ignore) == expected


def test_is_selected_default_is_all() -> None:
    assert is_selected("S001", "no-root-link", None)
    assert not is_selected("S001", "no-root-link", None, ["S"])


def test_unknown_selectors_and_find_rule() -> None:
    assert unknown_selectors(["ALL", "J", "S0", "unused-suppression", "Q", "J9"], RULES) == [
        "Q", "J9"]
    assert find_rule(RULES, "j101").name == "revolute-without-limit"
    assert find_rule(RULES, "no-root-link").code == "S001"
    assert find_rule(RULES, "J") is None
