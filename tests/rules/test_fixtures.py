"""Every rule over every fixture: the (code, line) pairs found must equal those marked.

A fixture marks an expected finding with `<!-- expect: CODE[, CODE] -->` on the line of the
offending element's start tag. Lines without a marker must stay clean.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from robotdesc.model.parse import parse_urdf
from robotdesc.rules.catalog import all_rules
from robotdesc.rules.registry import RuleContext, run_rule

FIXTURES = Path(__file__).parent / "fixtures"
MARKER = re.compile(r"<!--\s*expect:\s*([A-Z0-9,\s]+?)\s*-->")


def expected_findings(text: str) -> set[tuple[str, int]]:
    """The (code, line) pairs marked in a fixture."""
    expected = set()
    for number, line in enumerate(text.splitlines(), start=1):
        for match in MARKER.finditer(line):
            expected.update((code.strip(), number) for code in match.group(1).split(",")
                            if code.strip())
    return expected


def lint_lines(path: Path) -> set[tuple[str, int]]:
    """Run every rule with its default options; collect (code, line) of what they find."""
    robot = parse_urdf(path.read_bytes(), str(path))
    found = set()
    for rule_ in all_rules():
        for finding in run_rule(rule_, robot, RuleContext(options=rule_.default_options())):
            assert finding.where is not None, f"{rule_.code} finding without provenance"
            assert finding.where.span.path == str(path)
            assert finding.element, f"{rule_.code} finding without an element name"
            found.add((rule_.code, finding.where.span.line))
    return found


FIXTURE_FILES = sorted(FIXTURES.rglob("*.urdf"))


@pytest.mark.parametrize("path", FIXTURE_FILES, ids=lambda p: str(p.relative_to(FIXTURES)))
def test_fixture_findings_match_markers(path: Path) -> None:
    expected = expected_findings(path.read_text(encoding="utf-8"))
    found = lint_lines(path)
    assert sorted(found - expected) == [], "unexpected findings (code, line)"
    assert sorted(expected - found) == [], "expected findings not reported (code, line)"


def test_every_family_has_fixtures() -> None:
    families = {p.parent.name for p in FIXTURE_FILES}
    assert {"structure", "joints", "mimic", "transmissions", "gazebo", "visual", "paths",
            "clean"} <= families


def test_every_model_rule_is_exercised_by_a_fixture() -> None:
    marked = set()
    for path in FIXTURE_FILES:
        marked |= {code for code, _ in expected_findings(path.read_text(encoding="utf-8"))}
    model_rules = {r.code for r in all_rules() if not r.needs and r.family != "meta"}
    assert sorted(model_rules - marked) == []


def test_marker_parser_reads_several_codes() -> None:
    text = "<a/>\n<b/> <!-- expect: J101, S110 -->\n<c/><!--expect:P101-->\n"
    assert expected_findings(text) == {("J101", 2), ("S110", 2), ("P101", 3)}
