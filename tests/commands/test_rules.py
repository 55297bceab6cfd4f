"""`robotdesc rule CODE`: documentation, fix applicability, options with their defaults."""

from __future__ import annotations

import argparse

import pytest

from robotdesc.commands.rules import run_rule
from robotdesc.errors import UsageError
from robotdesc.rules.catalog import get_rule
from robotdesc.rules.docs import rule_help


def test_rule_help_lists_options_and_defaults() -> None:
    rule = get_rule("I201")
    assert rule is not None and rule.option_fields()
    text = rule_help(rule)
    assert text.startswith(f"I201 {rule.name}\n\nFamily: {rule.family}\n")
    assert "Fix: unsafe (applied by `robotdesc lint --fix` --unsafe-fixes)" in text
    assert "Options ([tool.robotdesc.rules.I201]):" in text
    field = rule.option_fields()[0]
    assert f"  {field.name} (" in text


def test_rule_without_options_says_so() -> None:
    rule = get_rule("RD001")
    assert rule is not None
    assert rule_help(rule).endswith("Options: none\n")


def test_unknown_rule_is_a_usage_error() -> None:
    with pytest.raises(UsageError, match="unknown rule 'Q999'"):
        run_rule(argparse.Namespace(code="Q999"))
