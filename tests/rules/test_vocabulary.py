"""Vocabulary rules (S201 unknown-element, S202 unknown-attribute, S203, J109, X201): the
marked fixtures, did-you-mean messages, the docs' examples, and silence on real robots."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from support import REPO, example_robot_urdfs

from robotdesc import cli
from robotdesc.expansion import ExpandOptions
from robotdesc.linting.driver import lint_file
from robotdesc.model.parse import parse_urdf
from robotdesc.rules.catalog import get_rule
from robotdesc.rules.registry import ExpansionFacts, RuleContext, SourceDocument, run_rule
from robotdesc.rules.urdf_vocabulary import URDF_ELEMENTS, parents_of

FIXTURES = Path(__file__).parent / "vocabulary_fixtures"
CODES = ("S201", "S202", "S203", "J109", "X201")
MARKER = re.compile(r"<!--\s*expect:\s*([A-Z0-9,\s]+?)\s*-->")
XML_FENCE = re.compile(r"```xml\n(.*?)```", re.DOTALL)
ENGINEER = REPO / "robots" / "engineer_description" / "urdf" / "engineer.urdf.xacro"


def marked(paths) -> set[tuple[str, str, int]]:
    found = set()
    for path in paths:
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            for match in MARKER.finditer(line):
                found |= {(code.strip(), path.name, number)
                          for code in match.group(1).split(",") if code.strip()}
    return found


def lint(path: Path, codes=CODES):
    return lint_file(str(path), select=list(codes),
                     expand_options=ExpandOptions(use_cache=False)).diagnostics


def run(code: str, xml: str, path: str = "r.urdf", from_xacro: bool = False):
    rule_ = get_rule(code)
    context = RuleContext(document=SourceDocument(xml.encode(), path),
                          expansion=ExpansionFacts(from_xacro=from_xacro))
    return list(run_rule(rule_, parse_urdf(xml.encode(), path), context))


CASES = [FIXTURES / "typos.urdf", FIXTURES / "extensions.urdf", FIXTURES / "xacro_snippet.urdf",
         FIXTURES / "xacro_in_text.urdf", FIXTURES / "legacy.urdf",
         FIXTURES / "xacro_pkg" / "urdf" / "arm.urdf.xacro"]


@pytest.mark.parametrize("path", CASES, ids=lambda p: p.name)
def test_fixture_findings_match_markers(path: Path) -> None:
    sources = [path] + (sorted(path.parent.glob("*.xacro")) if path.suffix == ".xacro" else [])
    found = {(d.code, Path(d.where.span.path).name, d.where.span.line) for d in lint(path)}
    expected = marked(sources)
    assert sorted(found - expected) == [], "unexpected findings"
    assert sorted(expected - found) == [], "expected findings not reported"


def test_messages_say_what_was_meant() -> None:
    messages = {(d.code, d.where.span.line): d.message for d in lint(FIXTURES / "typos.urdf")}
    assert "did you mean <inertial>?" in messages[("S201", 5)]
    assert "did you mean <origin>?" in messages[("S201", 9)]
    assert "it belongs in <collision> or <inertial> or <joint> or <visual>" \
        in messages[("S201", 12)]
    assert "<mu1> is a Gazebo tag: put it inside <gazebo reference=" in messages[("S201", 13)]
    assert "<gazebo> belongs at the top level of the robot" in messages[("S201", 14)]
    assert "did you mean 'iyz'?" in messages[("S202", 19)]  # the missing entry, not ixy
    assert "did you mean 'upper'?" in messages[("S202", 30)]
    assert "did you mean <color>?" in messages[("S201", 34)]


def test_legacy_joint_properties_name_dynamics() -> None:
    (finding,) = [d for d in lint(FIXTURES / "legacy.urdf") if d.code == "S201"]
    assert "early URDF's name for <dynamics>" in finding.message
    assert 'write <dynamics damping="..." friction="..."/>' in finding.message


def test_a_typo_in_a_macro_body_is_one_finding_with_the_expansion_count() -> None:
    findings = [d for d in lint(FIXTURES / "xacro_pkg" / "urdf" / "arm.urdf.xacro", ["S201"])]
    assert len(findings) == 1
    assert findings[0].message.endswith("(written once, expanded 2 times)")
    assert findings[0].where.macro_stack  # the call site comes along


def test_cli_json_reports_the_typo_at_its_line(capsys) -> None:
    code = cli.main(["lint", str(FIXTURES / "typos.urdf"), "--select", "S202",
                     "--format", "json", "--no-cache"])
    assert code == 1
    report = json.loads(capsys.readouterr().out)
    text = json.dumps(report)
    assert "has no attribute 'uper'" in text and "did you mean 'upper'?" in text


def test_negative_friction_is_found() -> None:
    xml = ("<robot name='r'><link name='a'/><link name='b'/>"
           "<joint name='j' type='continuous'><parent link='a'/><child link='b'/>"
           "<dynamics damping='0.1' friction='-0.2'/></joint></robot>")
    (finding,) = run("J109", xml)
    assert "friction=-0.2" in finding.message and finding.element == "joint:j/dynamics"


def test_document_rules_need_the_document() -> None:
    for code in ("S201", "S202", "X201"):
        assert "document" in get_rule(code).needs
        assert list(run_rule(get_rule(code), parse_urdf(b"<robot name='r'/>", "r.urdf"),
                             RuleContext())) == []


def test_x201_is_silent_for_expanded_xacro() -> None:
    xml = "<robot name='r'><link name='${a}'/></robot>"
    assert run("X201", xml, from_xacro=True) == []
    assert len(run("X201", xml)) == 1


@pytest.mark.parametrize("code", ["S201", "S202", "X201"])
def test_doc_example_is_found_and_fix_is_clean(code: str) -> None:
    bad, fixed = XML_FENCE.findall(get_rule(code).doc)
    wrap = ("<robot name='r'><link name='upper_arm'/><link name='forearm'/>{}</robot>"
            if code != "X201" else "<robot name='r'>{}</robot>")
    assert run(code, wrap.format(bad))
    assert run(code, wrap.format(fixed)) == []


def test_the_table_covers_urdfs_elements() -> None:
    robot = URDF_ELEMENTS["robot"]
    assert {"link", "joint", "material"} <= robot.children
    assert {"gazebo", "transmission", "ros2_control", "mujoco", "sensor"} <= {
        name for name, _ in robot.extension_children}
    assert URDF_ELEMENTS["joint"].children == {
        "origin", "parent", "child", "axis", "limit", "dynamics", "mimic",
        "safety_controller", "calibration"}
    assert URDF_ELEMENTS["inertia"].attributes == {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}
    assert parents_of("origin") == ["collision", "inertial", "joint", "visual"]


# --- real robots: the findings are the true ones, nothing else ---------------------------

#: Every finding of these rules on example-robot-data, all checked by hand (docs/precision.md).
KNOWN = {
    "S201": {"so101.urdf": 1, "tiago_dual.urdf": 4, "tiago_pro.urdf": 12},
    "S203": {"anymal.urdf": 12, "b1-z1.urdf": 1, "so100.urdf": 1, "z1.urdf": 1},
}


@pytest.mark.skipif(not example_robot_urdfs(), reason="example-robot-data is not installed")
def test_example_robot_data_gives_only_the_known_true_findings() -> None:
    counts: dict[str, dict[str, int]] = {}
    for path in example_robot_urdfs():
        xml = path.read_bytes()
        robot = parse_urdf(xml, str(path))
        context = RuleContext(document=SourceDocument(xml, str(path)))
        for code in CODES:
            for _ in run_rule(get_rule(code), robot, context):
                per_file = counts.setdefault(code, {})
                per_file[path.name] = per_file.get(path.name, 0) + 1
    assert counts == KNOWN


def test_engineer_is_silent() -> None:
    assert [(d.code, d.message) for d in lint(ENGINEER)] == []
