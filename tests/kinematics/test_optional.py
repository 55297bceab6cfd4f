import logging
import sys

import pytest

from kinematics.robots import ARM, robot
from robotdesc.kinematics.optional import KinematicsUnavailable, import_pinocchio
from robotdesc.rules.catalog import get_rule
from robotdesc.rules.registry import RuleContext, run_rule


def test_missing_pinocchio_is_an_input_error_that_says_how_to_install(monkeypatch) -> None:
    monkeypatch.setitem(sys.modules, "pinocchio", None)
    with pytest.raises(KinematicsUnavailable, match=r"pip install '\.\[kinematics\]'") as caught:
        import_pinocchio("robotdesc srdf")
    assert caught.value.exit_code == 2


def test_rules_needing_pinocchio_are_skipped_with_a_note(monkeypatch, caplog) -> None:
    from robotdesc.kinematics import optional

    monkeypatch.setattr(optional, "pinocchio_available", lambda: False)
    monkeypatch.setattr(optional, "_NOTED", set())
    caplog.set_level(logging.INFO, logger="robotdesc")  # shown with -v
    arm = robot(ARM)
    assert list(run_rule(get_rule("K201"), arm, RuleContext())) == []
    assert "K201 skipped: Pinocchio is not installed" in caplog.text


def test_a_lint_without_pinocchio_is_quiet_unless_kinematic_rules_are_selected(
        monkeypatch, tmp_path, capsys) -> None:
    from robotdesc.cli import main
    from robotdesc.commands import lint
    from robotdesc.kinematics import optional

    monkeypatch.setattr(optional, "pinocchio_available", lambda: False)
    monkeypatch.setattr(lint, "pinocchio_available", lambda: False)
    monkeypatch.setattr(optional, "_NOTED", set())
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    main(["lint", str(path)])
    assert "Pinocchio" not in capsys.readouterr().err  # every default lint would say it
    main(["lint", "--select", "K201", str(path)])
    assert "K201 skipped: Pinocchio is not installed" in capsys.readouterr().err
