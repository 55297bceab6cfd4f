"""D101 runs the settle test as a lint rule; it is opt-in, and the default lint never
imports MuJoCo."""

from __future__ import annotations

import subprocess
import sys

import pytest
from support import REPO

import robotdesc
from robotdesc.rules.catalog import all_rules, get_rule
from robotdesc.rules.registry import RuleContext, run_rule
from robotdesc.rules.select import select_rules

from .sim_support import FIXTURES

SLIP = str(FIXTURES / "slip_arm_unit_slip.urdf")


def test_rule_is_registered_opt_in() -> None:
    found = get_rule("D101")
    assert found.name == "fails-settle-test" and found.family == "sim" and found.opt_in
    assert found not in select_rules(all_rules(), None)
    for selector in ("ALL", "D", "D101", "fails-settle-test"):
        assert found in select_rules(all_rules(), [selector])
    assert found not in select_rules(all_rules(), ["D"], ["D101"])


def test_without_mesh_access_the_rule_does_nothing() -> None:
    robot = robotdesc.load(SLIP)
    assert list(run_rule(get_rule("D101"), robot, RuleContext())) == []


def test_default_lint_does_not_import_mujoco() -> None:
    code = ("import sys, robotdesc; robotdesc.lint(sys.argv[1]); "
            "print('mujoco' in sys.modules)")
    result = subprocess.run([sys.executable, "-c", code, SLIP], capture_output=True,
                            text=True, cwd=REPO, env={"PYTHONPATH": str(REPO / "src"),
                                                      "PATH": "/usr/bin:/bin"}, check=True)
    assert result.stdout.strip() == "False"


def test_selected_rule_reports_the_slipped_link() -> None:
    pytest.importorskip("mujoco")
    result = robotdesc.lint(SLIP, select=["D101"])
    links = {d.element for d in result.diagnostics}
    assert "link:wrist_roll_link" in links
    wrist = [d for d in result.diagnostics if d.element == "link:wrist_roll_link"]
    assert all(d.code == "D101" for d in wrist)
    assert wrist[0].where.span.line == 39  # the <link name="wrist_roll_link"> line
    assert any("finite check" in d.message for d in wrist)


def test_selected_rule_is_clean_on_the_correct_arm() -> None:
    pytest.importorskip("mujoco")
    assert robotdesc.lint(str(FIXTURES / "slip_arm.urdf"), select=["D"]).diagnostics == ()
