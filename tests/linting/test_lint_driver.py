"""The lint pipeline on plain URDF files, with small stand-in rules (the real rules are tested
in tests/rules): selection, options, severity overrides, per-file ignores, suppressions,
RD001, crashing rules, and the LintResult API."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pytest

import robotdesc
from robotdesc import linting
from robotdesc.config import Config
from robotdesc.diagnostics import Finding, Severity
from robotdesc.errors import XmlSyntaxError
from robotdesc.linting.driver import lint_file
from robotdesc.linting.result import RuleCrashed
from robotdesc.rules import catalog
from robotdesc.rules.registry import Rule

URDF = """<robot name="r">
  <link name="base"/>
  <link name="arm"/>
  <!-- robotdesc: ignore T001 -->
  <joint name="quiet" type="fixed"><parent link="base"/><child link="arm"/></joint>
  <joint name="loud" type="fixed"><parent link="base"/><child link="arm"/></joint>
  <!-- robotdesc: ignore T003, T777 -->
  <link name="tip"/>
</robot>
"""


@dataclass(frozen=True)
class EchoOptions:
    threshold: int = 1


def joint_seen(robot, ctx):
    """Reports every joint."""
    for joint in robot.joints:
        yield Finding(f"joint {joint.name}", joint.where, f"joint:{joint.name}")


def robot_info(robot, ctx):
    """Reports the robot, without a location."""
    yield Finding(f"robot {robot.name} from_xacro={ctx.expansion.from_xacro}")


def option_echo(robot, ctx):
    """Echoes its option."""
    yield Finding(f"threshold={ctx.options.threshold}", robot.links[0].where, "link:base")


def nothing(robot, ctx):
    """Yields nothing (RD001 is emitted by the driver)."""
    return ()


def crash(robot, ctx):
    """Always fails."""
    raise ZeroDivisionError("boom")
    yield  # pragma: no cover


RULES = [
    Rule("T001", "joint-seen", "test", Severity.ERROR, joint_seen),
    Rule("T002", "robot-info", "test", Severity.INFO, robot_info),
    Rule("T003", "option-echo", "test", Severity.WARNING, option_echo, EchoOptions),
    Rule("RD001", "unused-suppression", "suppression", Severity.WARNING, nothing),
]


@pytest.fixture
def rules(monkeypatch: pytest.MonkeyPatch) -> list[Rule]:
    active = list(RULES)
    monkeypatch.setattr(catalog, "all_rules", lambda: list(active))
    return active


@pytest.fixture
def urdf(tmp_path: Path) -> Path:
    path = tmp_path / "robot.urdf"
    path.write_text(URDF, encoding="utf-8")
    return path


def summary(result) -> list[tuple[str, int, str, str]]:
    return [(d.code, d.where.span.line, str(d.severity), d.message) for d in result.diagnostics]


def test_default_run_sorts_suppresses_and_reports_unused(rules, urdf: Path) -> None:
    result = lint_file(str(urdf), Config())
    assert summary(result) == [
        ("T002", 1, "info", "robot r from_xacro=False"),
        ("T003", 2, "warning", "threshold=1"),
        ("T001", 6, "error", "joint loud"),
        ("RD001", 7, "warning", "suppression names unknown rule 'T777'"),
        ("RD001", 7, "warning",
         "unused suppression: no T003 finding on this line or the next"),
    ]
    assert result.target == str(urdf)
    assert all(d.target == str(urdf) for d in result.diagnostics)
    assert result.suppressed == 1
    assert result.rules_run == ("T001", "T002", "T003", "RD001")
    assert result.counts == {Severity.ERROR: 1, Severity.WARNING: 3, Severity.INFO: 1}
    assert result.failed(Severity.ERROR) and result.failed(Severity.INFO)


def test_config_options_severity_and_ignore(rules, urdf: Path) -> None:
    config = Config(ignore=("RD",), rule_options=(("T003", EchoOptions(threshold=7)),),
                    severity=(("T001", Severity.INFO),))
    result = lint_file(str(urdf), config)
    assert summary(result) == [("T002", 1, "info", "robot r from_xacro=False"),
                               ("T003", 2, "warning", "threshold=7"),
                               ("T001", 6, "info", "joint loud")]
    assert not result.failed(Severity.WARNING + 1)


def test_cli_select_replaces_config_select_and_ignore_adds(rules, urdf: Path) -> None:
    config = Config(select=("T002",), ignore=("T003",))
    assert [d.code for d in lint_file(str(urdf), config).diagnostics] == ["T002"]
    result = lint_file(str(urdf), config, select=["T"], ignore=["robot-info"])
    assert [d.code for d in result.diagnostics] == ["T001"]


def test_unused_suppression_of_a_rule_that_did_not_run_is_not_reported(rules,
                                                                       urdf: Path) -> None:
    result = lint_file(str(urdf), Config(select=("T002", "RD001")))
    assert [d.message for d in result.diagnostics if d.code == "RD001"] == [
        "suppression names unknown rule 'T777'"]


def test_per_file_ignores_match_relative_to_the_config(rules, urdf: Path) -> None:
    config_path = str(urdf.parent / "robotdesc.toml")
    config = Config(path=config_path, per_file_ignores=(("*.urdf", ("T00",)),))
    result = lint_file(str(urdf), config)
    # the T001 comment now suppresses nothing, so it is reported too
    assert [(d.code, d.where.span.line) for d in result.diagnostics] == [
        ("RD001", 4), ("RD001", 7), ("RD001", 7)]
    elsewhere = Config(path=config_path, per_file_ignores=(("vendor/*.urdf", ("T",)),))
    assert len(lint_file(str(urdf), elsewhere).diagnostics) == 5


def test_a_crashing_rule_is_reported_by_code(rules, urdf: Path) -> None:
    rules.append(Rule("T009", "always-crashes", "test", Severity.ERROR, crash))
    with pytest.raises(RuleCrashed, match=r"rule T009 \(always-crashes\) crashed on .*"
                                          r"ZeroDivisionError: boom") as caught:
        lint_file(str(urdf), Config())
    assert caught.value.exit_code == 3
    assert isinstance(caught.value.__cause__, ZeroDivisionError)


def test_malformed_xml_is_an_input_error(rules, tmp_path: Path) -> None:
    broken = tmp_path / "broken.urdf"
    broken.write_text('<robot name="r">\n  <link name="a">\n</robot>\n')
    with pytest.raises(XmlSyntaxError) as caught:
        lint_file(str(broken), Config())
    assert caught.value.span.path.endswith("broken.urdf")
    assert caught.value.span.line >= 2


def test_result_api(rules, urdf: Path) -> None:
    result = lint_file(str(urdf), Config(select=("T001",)))
    assert repr(result) == f"<LintResult {str(urdf)!r}: 1 error, 0 warning, 0 info>"
    table = result._repr_html_()
    assert table.startswith("<table>") and "<td>T001</td>" in table and "joint loud" in table
    document = robotdesc.json_report(result)
    assert document["summary"]["error"] == 1
    assert document["diagnostics"][0]["element"] == "joint:loud"
    assert result.robot.name == "r" and result.expanded.source == str(urdf)


def test_package_all_names_every_lazy_attribute() -> None:
    assert linting.__all__ == sorted(linting._LAZY)
    for name in linting.__all__:
        assert getattr(linting, name) is not None
