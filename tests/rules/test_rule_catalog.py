"""The catalog registers every rule with a well-formed code, name, family and severity."""

from __future__ import annotations

import re

import pytest

from robotdesc.diagnostics import Severity
from robotdesc.rules.catalog import all_rules, get_rule
from robotdesc.rules.registry import FAMILIES, rule

CODE = re.compile(r"^[A-Z]{1,3}\d{3}$")
NAME = re.compile(r"^[a-z0-9]+(-[a-z0-9]+)*$")


def test_codes_and_names_are_well_formed_and_unique() -> None:
    rules = all_rules()
    assert len(rules) >= 34
    for rule_ in rules:
        assert CODE.match(rule_.code), rule_.code
        assert NAME.match(rule_.name), rule_.name
        assert isinstance(rule_.severity, Severity)
    assert len({r.name for r in rules}) == len(rules)


def test_families_match_code_prefixes() -> None:
    for rule_ in all_rules():
        assert rule_.code.startswith(FAMILIES[rule_.family]), (rule_.code, rule_.family)


def test_a_rule_of_an_undeclared_family_or_prefix_is_refused() -> None:
    with pytest.raises(RuntimeError, match="FAMILIES"):
        rule("Z999", "no-such-family", family="nowhere")(lambda robot, ctx: iter(()))
    with pytest.raises(RuntimeError, match="FAMILIES"):
        rule("Q101", "wrong-prefix", family="joints")(lambda robot, ctx: iter(()))


def test_lookup_by_code_or_name() -> None:
    assert get_rule("j102").name == "missing-joint-limit"
    assert get_rule("unused-suppression").code == "RD001"
    assert get_rule("X101").needs == frozenset({"expansion"})
    assert get_rule("X101").default_options().max_depth == 16
