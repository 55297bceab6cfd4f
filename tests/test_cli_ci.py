"""`robotdesc lint` as a CI gate on the workspace fixture: discovery message, variant names,
exit codes, every report format, --statistics, --jobs."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from lxml import etree

REPO = Path(__file__).resolve().parents[1]
WORKSPACE = REPO / "tests" / "fixtures" / "ci_workspace"


def run(*args: str, cwd: Path = WORKSPACE) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(REPO / "src"), NO_COLOR="1")
    return subprocess.run([sys.executable, "-m", "robotdesc", *args], cwd=cwd, env=env,
                          capture_output=True, text=True, check=False)


def test_workspace_discovery_naming_and_exit_code() -> None:
    proc = run("lint", ".", "--format", "json")
    assert proc.returncode == 1, proc.stderr
    assert ("linting 3 target(s): src/arm_description/urdf/arm.urdf.xacro[arm_type=short], "
            "src/arm_description/urdf/arm.urdf.xacro[arm_type=long], "
            "src/base_description/urdf/base.urdf; skipped 2 macro libraries") in proc.stderr
    document = json.loads(proc.stdout)
    assert document["summary"]["files_checked"] == 3
    found = [(d["code"], Path(d["file"]).name, d["line"], d["variant"])
             for d in document["diagnostics"]]
    assert found == [("J102", "arm_macro.xacro", 13, {"arm_type": "long"}),
                     ("J107", "base.urdf", 8, {})]
    assert run("lint", ".", "--fail-on", "error", "--select", "J107").returncode == 0
    assert run("lint", "src/base_description").returncode == 1


def test_text_report_names_the_variant() -> None:
    proc = run("lint", "src/arm_description")
    assert proc.returncode == 1
    assert "J102 [error] revolute joint 'arm_elbow' has no <limit> (only in variant [arm_type=long])" \
        in proc.stdout


@pytest.mark.parametrize("fmt", ["sarif", "junit", "github", "gitlab", "json", "text"])
def test_every_format_writes_to_the_output_file(tmp_path, fmt: str) -> None:
    out = tmp_path / f"report.{fmt}"
    proc = run("lint", ".", "--format", fmt, "--output-file", str(out), "--jobs", "2")
    assert proc.returncode == 1 and proc.stdout == "", proc.stderr
    text = out.read_text(encoding="utf-8")
    if fmt in ("sarif", "json", "gitlab"):
        json.loads(text)
    elif fmt == "junit":
        assert etree.fromstring(text.encode()).get("failures") == "2"
    elif fmt == "github":
        assert text.startswith("::error file=src/arm_description/urdf/arm_macro.xacro,line=13,")
    assert "arm_macro.xacro" in text


def test_statistics() -> None:
    proc = run("lint", ".", "--statistics")
    assert proc.returncode == 1
    assert proc.stdout.splitlines()[1:] == [
        "    1  J102  missing-joint-limit  error",
        "    1  J107  axis-not-normalized  warning",
        "    2  total"]
    assert run("lint", ".", "--statistics", "--format", "sarif").returncode == 2


def test_input_errors_still_produce_a_report(tmp_path) -> None:
    (tmp_path / "broken.urdf").write_text("<robot name='b'><link></robot>")
    proc = run("lint", "broken.urdf", "--format", "sarif", cwd=tmp_path)
    assert proc.returncode == 2
    invocation = json.loads(proc.stdout)["runs"][0]["invocations"][0]
    assert invocation["executionSuccessful"] is False


def test_bad_jobs_is_a_usage_error() -> None:
    assert run("lint", ".", "--jobs", "-1").returncode == 2
