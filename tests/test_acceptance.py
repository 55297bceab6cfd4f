"""Issue-level acceptance: findings inside macros, and every example-robot-data URDF linted."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from support import REPO, example_robot_urdfs

HAND = REPO / "tests" / "fixtures" / "macro_twice" / "urdf" / "hand.urdf.xacro"
FINGER = HAND.with_name("finger.xacro")


def _lint_json(*argv: str) -> tuple[int, dict, str]:
    done = subprocess.run([sys.executable, "-m", "robotdesc", "lint", "--format", "json", *argv],
                          capture_output=True, text=True, timeout=600, cwd=REPO)
    return done.returncode, json.loads(done.stdout), done.stderr


def test_finding_in_a_macro_used_twice_points_at_the_body_with_each_call_site():
    code, report, _ = _lint_json(str(HAND))
    assert code == 1
    found = [(d["code"], d["file"], d["line"], tuple((s["file"], s["line"]) for s in d["macro_stack"]),
              d["elements"]) for d in report["diagnostics"]]
    assert found == [  # one problem in the macro body, made twice: one finding, both elements
        ("J102", str(FINGER), 10, ((str(HAND), 15),),
         ["joint:left_finger_joint", "joint:right_finger_joint"]),
    ]
    text = subprocess.run([sys.executable, "-m", "robotdesc", "lint", str(HAND)],
                          capture_output=True, text=True, timeout=600, cwd=REPO).stdout
    assert "hand.urdf.xacro:15)" in text and "hand.urdf.xacro:16)" in text  # each call site


@pytest.mark.skipif(not example_robot_urdfs(), reason="example-robot-data is not installed")
def test_every_example_robot_data_urdf_lints_without_an_internal_error():
    urdfs = [str(p) for p in example_robot_urdfs()]
    assert len(urdfs) >= 60
    code, report, stderr = _lint_json(*urdfs)
    assert code in (0, 1), stderr
    assert "Traceback" not in stderr
    assert report["summary"]["files_checked"] == len(urdfs)
    assert report["failures"] == []
