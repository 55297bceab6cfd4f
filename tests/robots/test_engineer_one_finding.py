"""One finding per problem on the Engineer: a swapped limit planted in the arm joint macro (made
twice, shoulder and elbow, in each of the package's 3 config variants) is one annotation, one
SARIF result, one text finding naming both joints and the variants, and one fix."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[2] / "robots" / "engineer_description"
ARM_LIMIT = '<limit lower="${lower}" upper="${upper}"'
SWAPPED = '<limit lower="0.5" upper="-0.5"'


@pytest.fixture(scope="module")
def planted(tmp_path_factory) -> Path:
    """A copy of the package with the arm macro's limit swapped (lower > upper)."""
    copy = tmp_path_factory.mktemp("engineer") / "engineer_description"
    shutil.copytree(PACKAGE, copy)
    arm = copy / "urdf" / "arm.xacro"
    text = arm.read_text(encoding="utf-8")
    assert text.count(ARM_LIMIT) == 1
    arm.write_text(text.replace(ARM_LIMIT, SWAPPED), encoding="utf-8")
    return copy


def _lint(package: Path, *argv: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "robotdesc", "lint", "-q",
                           "urdf/engineer.urdf.xacro", *argv],
                          capture_output=True, text=True, timeout=600, cwd=package)


@pytest.mark.slow
def test_a_swapped_limit_in_a_shared_macro_is_one_finding(planted) -> None:
    github = _lint(planted, "--format", "github")
    assert github.returncode == 1, github.stderr
    annotations = [line for line in github.stdout.splitlines() if line.startswith("::")]
    assert len(annotations) == 1, github.stdout
    assert "title=J103" in annotations[0] and "file=urdf/arm.xacro,line=17" in annotations[0]

    sarif = json.loads(_lint(planted, "--format", "sarif").stdout)
    (result,) = sarif["runs"][0]["results"]
    assert result["properties"]["elements"] == ["joint:elbow", "joint:shoulder"]
    assert len(result["properties"]["variants"]) == 3 and result["properties"]["inAllVariants"]

    text = _lint(planted).stdout
    assert text.count("J103 [error]") == 1, text
    assert "2 elements: joint:elbow" in text and "joint:shoulder" in text
    assert "in all 3 variants: [default arguments], " \
           "[main_track_wheels=18,flipper_track_wheels=31], [with_gripper=false]" in text
    assert "Found 1 error in 1 file." in text

    fixed = _lint(planted, "--fix", "--unsafe-fixes")
    assert "fixed 1 finding(s) in 1 file(s)" in fixed.stderr, fixed.stderr
    assert fixed.returncode == 0, fixed.stdout
    arm = (planted / "urdf" / "arm.xacro").read_text(encoding="utf-8")
    assert '<limit lower="-0.5" upper="0.5"' in arm
