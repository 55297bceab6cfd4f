"""X101 deep-macro-recursion reads the expansion facts, not the URDF."""

from __future__ import annotations

from robotdesc.expansion.result import MacroRecursion
from robotdesc.model.elements import Robot
from robotdesc.rules.catalog import get_rule
from robotdesc.rules.registry import ExpansionFacts, RuleContext
from robotdesc.rules.xacro import MacroRecursionOptions
from robotdesc.source import Span

RULE = get_rule("deep-macro-recursion")
WHEELS = MacroRecursion("wheels", 212, Span("rover.urdf.xacro", 12),
                        Span("rover.urdf.xacro", 40))
SHALLOW = MacroRecursion("halves", 8, Span("rover.urdf.xacro", 60))


def findings(*recursions, options=None):
    ctx = RuleContext(options=options or RULE.default_options(),
                      expansion=ExpansionFacts(macro_recursion=recursions, from_xacro=True))
    return list(RULE.check(Robot("rover"), ctx))


def test_deep_recursion_reported_at_the_macro_definition() -> None:
    [finding] = findings(WHEELS, SHALLOW)
    assert finding.where.span == Span("rover.urdf.xacro", 12)
    assert finding.element == "macro:wheels"
    assert "212 levels" in finding.message
    assert "super-linearly" in finding.message
    assert "log2(n)" in finding.message
    assert "rover.urdf.xacro:40" in finding.message


def test_depth_at_the_limit_is_accepted() -> None:
    assert findings(MacroRecursion("m", 16, Span("a.xacro", 1))) == []
    assert len(findings(MacroRecursion("m", 17, Span("a.xacro", 1)))) == 1


def test_max_depth_option() -> None:
    assert len(findings(SHALLOW, options=MacroRecursionOptions(max_depth=4))) == 1


def test_plain_urdf_has_no_expansion_facts() -> None:
    assert list(RULE.check(Robot("r"), RuleContext())) == []
