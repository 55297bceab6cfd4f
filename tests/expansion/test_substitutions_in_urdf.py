"""A .urdf that still holds xacro substitutions: `robotdesc expand` evaluates them as the
xacro command does (the corpus' ros2_kortex gen3_2f85.urdf); the lint reads the file as a URDF
consumer would and reports them once (X201)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from robotdesc.expansion import ExpandOptions, expand_file

URDF = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/>
  <ros2_control name="arm" type="system">
    <joint name="joint_1">
      <command_interface name="position"><param name="min">${-2*pi}</param></command_interface>
    </joint>
  </ros2_control>
</robot>
"""


@pytest.fixture
def urdf(tmp_path: Path) -> Path:
    path = tmp_path / "gen3.urdf"
    path.write_text(URDF)
    return path


def test_expand_option_evaluates_like_xacro(urdf: Path) -> None:
    plain = expand_file(urdf, options=ExpandOptions(use_cache=False))
    assert b"${-2*pi}" in plain.xml and not plain.from_xacro
    evaluated = expand_file(urdf, options=ExpandOptions(use_cache=False,
                                                        substitutions_in_urdf=True))
    assert b"-6.283185307179586" in evaluated.xml


def _cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "robotdesc", *args], check=False,
                          capture_output=True, text=True, timeout=120,
                          env={"ROBOTDESC_CACHE_DIR": "off", "PATH": "/usr/bin:/bin"})


def test_expand_command_evaluates_and_says_so(urdf: Path) -> None:
    run = _cli("expand", str(urdf))
    assert run.returncode == 0, run.stderr
    assert "<param name=\"min\">-6.283185307179586</param>" in run.stdout
    assert "holds xacro substitutions" in run.stderr


def test_lint_reports_the_leftover_substitution_once(urdf: Path) -> None:
    run = _cli("lint", str(urdf), "--format", "json")
    codes = [d["code"] for d in json.loads(run.stdout)["diagnostics"]]
    assert codes.count("X201") == 1
