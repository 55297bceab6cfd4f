"""Baselines: findings matched by target, code, element and message (not line), counted."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from robotdesc.diagnostics import Diagnostic, Severity
from robotdesc.errors import InputError
from robotdesc.linting.baseline import apply_baseline, read_baseline, render_baseline
from robotdesc.linting.result import LintResult
from robotdesc.source import Provenance, Span

SRC = Path(__file__).resolve().parents[2] / "src"

ROBOT = """<?xml version="1.0"?>
<robot name="r">
  <link name="a"/>
  <link name="b"/>
  <link name="c"/>
  <joint name="j1" type="continuous">
    <parent link="a"/>
    <child link="b"/>
    <axis xyz="0 0 2"/>
  </joint>
{extra}</robot>
"""
SECOND_BAD_JOINT = """  <joint name="j2" type="continuous">
    <parent link="b"/>
    <child link="c"/>
    <axis xyz="3 0 0"/>
  </joint>
"""
FINE_JOINT = SECOND_BAD_JOINT.replace("3 0 0", "1 0 0")


def lint(cwd: Path, *args: str) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(SRC), NO_COLOR="1")
    return subprocess.run([sys.executable, "-m", "robotdesc", "lint", *args,
                           "--select", "J", "--format", "json"],
                          cwd=cwd, capture_output=True, text=True, env=env, check=False)


def test_edits_above_do_not_resurrect_and_new_findings_are_reported(tmp_path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text(ROBOT.format(extra=FINE_JOINT))
    written = lint(tmp_path, "robot.urdf", "--write-baseline", "baseline.json")
    assert written.returncode == 0, written.stderr
    assert json.loads(written.stdout)["diagnostics"] == []
    baseline = json.loads((tmp_path / "baseline.json").read_text())
    assert baseline["findings"] == [{"target": "robot.urdf", "code": "J107",
                                     "element": "joint:j1", "count": 1,
                                     "message": baseline["findings"][0]["message"]}]

    shifted = ROBOT.replace('<robot name="r">', '<robot name="r">\n  <!-- a -->\n  <!-- b -->')
    robot.write_text(shifted.format(extra=FINE_JOINT))
    again = lint(tmp_path, "robot.urdf", "--baseline", "baseline.json")
    assert again.returncode == 0 and json.loads(again.stdout)["diagnostics"] == []
    assert "1 finding(s) hidden by the baseline" in again.stderr

    robot.write_text(shifted.format(extra=SECOND_BAD_JOINT))
    new = lint(tmp_path, "robot.urdf", "--baseline", "baseline.json")
    assert new.returncode == 1
    assert [(d["code"], d["element"]) for d in json.loads(new.stdout)["diagnostics"]] == \
        [("J107", "joint:j2")]

    without = lint(tmp_path, "robot.urdf")
    assert len(json.loads(without.stdout)["diagnostics"]) == 2


def _result(tmp_path: Path, count: int) -> LintResult:
    where = Provenance(Span(str(tmp_path / "arm.xacro"), 3))
    diagnostic = Diagnostic("J102", "missing-joint-limit", Severity.ERROR,
                            f"joint 'elbow' in {tmp_path}/arm.xacro has no <limit>", where,
                            "joint:elbow", None, str(tmp_path / "robot.urdf.xacro"))
    return LintResult(str(tmp_path / "robot.urdf.xacro"), (diagnostic,) * count,
                      variant=(("side", "left"),))


def test_counts_and_stale_entries(tmp_path) -> None:
    path = tmp_path / "baseline.json"
    path.write_text(render_baseline([_result(tmp_path, 2)], str(path)))
    (entry,) = json.loads(path.read_text())["findings"]
    assert entry["target"] == "robot.urdf.xacro[side=left]" and entry["count"] == 2
    assert str(tmp_path) not in entry["message"]  # portable across checkouts
    recorded = read_baseline(str(path))
    three = apply_baseline([_result(tmp_path, 3)], recorded, str(tmp_path))
    assert (three.matched, three.stale, len(three.results[0].diagnostics)) == (2, 0, 1)
    one = apply_baseline([_result(tmp_path, 1)], recorded, str(tmp_path))
    assert (one.matched, one.stale, len(one.results[0].diagnostics)) == (1, 1, 0)


@pytest.mark.parametrize("text", ["{", "[]", '{"robotdesc_baseline": 1, "findings": [{}]}'])
def test_bad_baseline_is_an_input_error(tmp_path, text: str) -> None:
    path = tmp_path / "baseline.json"
    path.write_text(text)
    with pytest.raises(InputError) as info:
        read_baseline(str(path))
    assert info.value.span.path == str(path)
