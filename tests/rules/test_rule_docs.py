"""Rule documentation: every docstring has its three parts, its examples are true, and
docs/rules.md is current."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from robotdesc.model.parse import parse_urdf
from robotdesc.rules.catalog import all_rules
from robotdesc.rules.docs import REGENERATE, REGENERATE_INDEX, render_index, render_rules_markdown
from robotdesc.rules.index import INDEX_FILE
from robotdesc.rules.registry import RuleContext, run_rule

RULES_MD = Path(__file__).resolve().parents[2] / "docs" / "rules.md"
XML_FENCE = re.compile(r"```xml\n(.*?)```", re.DOTALL)
#: Example fences: XML, or the YAML and launch files the R1xx rules judge.
EXAMPLE_FENCE = re.compile(r"```(?:xml|yaml|python)\n(.*?)```", re.DOTALL)
RULES = all_rules()


@pytest.mark.parametrize("rule_", RULES, ids=lambda r: r.code)
def test_docstring_has_summary_why_and_example(rule_) -> None:
    lines = rule_.doc.splitlines()
    assert rule_.summary and not rule_.summary.startswith(("Why", "Example"))
    assert "Why is this bad?" in lines
    assert "Example" in lines
    assert lines.index("Why is this bad?") < lines.index("Example")
    examples = EXAMPLE_FENCE.findall(rule_.doc.split("\nExample\n", 1)[1])
    assert len(examples) == 2, "an Example section shows the bad XML, then the fix"


def _robot_examples():
    for rule_ in RULES:
        examples = XML_FENCE.findall(rule_.doc)
        if len(examples) == 2 and examples[0].lstrip().startswith("<robot"):
            yield pytest.param(rule_, examples[0], examples[1], id=rule_.code)


@pytest.mark.parametrize(("rule_", "bad", "fixed"), list(_robot_examples()))
def test_example_is_found_and_fix_is_clean(rule_, bad: str, fixed: str) -> None:
    ctx = RuleContext(options=rule_.default_options())
    found = list(run_rule(rule_, parse_urdf(bad.encode(), "bad.urdf"), ctx))
    assert found, f"{rule_.code} finds nothing in its own example"
    assert list(run_rule(rule_, parse_urdf(fixed.encode(), "fixed.urdf"), ctx)) == []


def test_most_rules_have_runnable_robot_examples() -> None:
    runnable = {param.values[0].code for param in _robot_examples()}
    model_rules = {r.code for r in RULES if not r.needs and r.family != "meta"}
    assert sorted(model_rules - runnable) == []


def test_rendered_markdown_lists_every_rule_with_options() -> None:
    text = render_rules_markdown()
    for rule_ in RULES:
        assert f"## {rule_.code} {rule_.name}" in text
        assert f"| [{rule_.code}](#{rule_.code.lower()}-{rule_.name}) |" in text
    assert "| `max_depth` | int | `16` |" in text
    assert "| `tolerance` | float | `0.001` |" in text
    assert "### Why is this bad?" in text


def test_docs_rules_md_is_current() -> None:
    expected = render_rules_markdown()
    actual = RULES_MD.read_text(encoding="utf-8") if RULES_MD.exists() else ""
    assert actual == expected, f"docs/rules.md is out of date; regenerate it with `{REGENERATE}`"


def test_the_rule_index_is_current() -> None:
    """`robotdesc rules` and `rule CODE` read it (tests/test_startup.py)."""
    actual = Path(INDEX_FILE).read_text(encoding="utf-8") if Path(INDEX_FILE).exists() else ""
    assert actual == render_index(), f"the rule index is out of date; regenerate it with " \
                                     f"`{REGENERATE_INDEX}`"
