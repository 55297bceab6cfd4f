"""SRDF files (MoveIt semantic descriptions, root `<robot>` too) are not linted as URDF:
a folder lint skips them with a note; one given alone is a clear error, exit 2 (issue 14:
an SRDF linted as a URDF gave S001 and hundreds of S201 on Interbotix's packages)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from robotdesc.linting.targets import discover_targets, is_srdf

SRDF = """<?xml version="1.0"?>
<robot name="arm">
  <group name="arm"><chain base_link="base" tip_link="tool"/></group>
  <disable_collisions link1="base" link2="link1" reason="Adjacent"/>
</robot>
"""
SRDF_XACRO = """<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="robot_name" default="arm"/>
  <group name="$(arg robot_name)"/>
</robot>
"""
URDF = """<?xml version="1.0"?>
<robot name="arm"><link name="base"/></robot>
"""


def _package(root: Path) -> Path:
    (root / "urdf").mkdir(parents=True)
    (root / "config").mkdir()
    (root / "urdf" / "arm.urdf").write_text(URDF)
    (root / "config" / "arm.srdf").write_text(SRDF)
    (root / "config" / "arm.srdf.xacro").write_text(SRDF_XACRO)
    (root / "config" / "semantic.urdf").write_text(SRDF)  # an SRDF by content, wrong name
    return root


def test_recognised_by_name_or_content(tmp_path: Path) -> None:
    root = _package(tmp_path)
    assert is_srdf(str(root / "config" / "arm.srdf.xacro"))
    assert is_srdf(str(root / "config" / "semantic.urdf"))
    assert not is_srdf(str(root / "urdf" / "arm.urdf"))


def test_folder_lint_skips_them(tmp_path: Path) -> None:
    root = _package(tmp_path)
    discovery = discover_targets(str(root))
    assert [Path(t.path).name for t in discovery.targets] == ["arm.urdf"]


def _lint(path: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "robotdesc", "lint", str(path)], check=False,
                          capture_output=True, text=True, timeout=120,
                          env={"ROBOTDESC_CACHE_DIR": "off", "PATH": "/usr/bin:/bin"})


def test_cli_folder_lint_says_what_it_skipped(tmp_path: Path) -> None:
    run = _lint(_package(tmp_path))
    assert run.returncode == 0, run.stdout + run.stderr
    assert "skipped 2 SRDF file(s)" in run.stderr
    assert "S001" not in run.stdout and "S201" not in run.stdout


def test_cli_single_srdf_is_a_clear_error(tmp_path: Path) -> None:
    root = _package(tmp_path)
    for name in ("arm.srdf", "arm.srdf.xacro", "semantic.urdf"):
        run = _lint(root / "config" / name)
        assert run.returncode == 2, run.stdout + run.stderr
        assert "this is an SRDF" in run.stdout + run.stderr
        assert "Traceback" not in run.stderr
