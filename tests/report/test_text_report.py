"""The text report: location line, source line with caret, macro chain, fix, summary."""

from __future__ import annotations

import contextlib
import io
import re

import pytest

from robotdesc.linting.result import LintResult
from robotdesc.report.text import render_failure, render_text, summary_line, write_text

from .report_samples import build_sample


@pytest.fixture
def sample(tmp_path):
    return build_sample(tmp_path)


def test_text_report_snapshot(sample) -> None:
    results, failures, root = sample
    text = render_text(results, failures, cwd=str(root))
    assert text == (
        "arm.xacro:3:2: J101 [error] revolute joint 'left_elbow' has no <limit>\n"
        "  |\n"
        "3 |     <joint name=\"${prefix}elbow\" type=\"revolute\">\n"
        "  |     ^^^^^^\n"
        "  = in macro called from robot.urdf.xacro:3\n"
        "  = in macro called from robot.urdf.xacro:4\n"
        "  = fix:\n"
        "    <limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>\n"
        "\n"
        "robot.urdf.xacro:5: S003 [warning] link 'base' clashes\n"
        "  |\n"
        "5 |   <link name=\"base\"/>\n"
        "  |   ^^^^^\n"
        "\n"
        "robot.urdf.xacro: X001 [info] note\n"
        "\n"
        "Found 1 error, 1 warning, 1 info in 2 files. 1 file could not be checked.\n"
        "Read 1 file; 2 findings suppressed (2 by inline comments).\n"
    )


def test_paths_outside_cwd_stay_absolute(sample, tmp_path_factory) -> None:
    results, _, root = sample
    elsewhere = tmp_path_factory.mktemp("elsewhere")
    text = render_text(results, cwd=str(elsewhere), show_source=False)
    assert text.startswith(f"{root / 'arm.xacro'}:3:2: J101 [error]")
    assert "  |" not in text.splitlines()[1]


def test_failure_text_names_file_line_and_call_chain(sample) -> None:
    _, failures, root = sample
    assert render_failure(failures[0], cwd=str(root)) == (
        "broken.urdf.xacro:2:3: error: undefined property 'undefined'\n"
        "  |\n"
        "2 |   <link name='${undefined}'/>\n"
        "  |   ^^^^^\n"
        "  = in macro called from robot.urdf.xacro:9\n"
    )


def test_summary_when_clean() -> None:
    clean = [LintResult("/a.urdf", ()), LintResult("/b.urdf", ())]
    assert "".join(t for t, _ in summary_line(clean)) == "All checks passed (2 files checked)."


def test_colour_output_uses_ansi_codes_and_same_text(sample) -> None:
    results, failures, root = sample
    plain, coloured = io.StringIO(), io.StringIO()
    write_text(plain, results, failures, colour=False, cwd=str(root))
    write_text(coloured, results, failures, colour=True, cwd=str(root))
    assert "\x1b[" not in plain.getvalue()
    assert "\x1b[" in coloured.getvalue()
    stripped = re.sub(r"\x1b\[[0-9;]*m", "", coloured.getvalue())
    assert stripped == plain.getvalue()


def test_summary_names_variants_suppressions_and_files_read(tmp_path) -> None:
    import dataclasses

    from robotdesc.linting.result import LintResult

    target = str(tmp_path / "robot.urdf.xacro")
    base = LintResult(target, (), suppressed=260, config_path=None)
    results = [base, dataclasses.replace(base, args=(("wheels", "18"),), suppressed=0,
                                         suppressed_by_baseline=3),
               dataclasses.replace(base, args=(("gripper", "false"),), suppressed=0,
                                   suppressed_by_config=1)]
    text = render_text(results, cwd=str(tmp_path))
    assert text.splitlines() == [
        "All checks passed (3 variants of 1 file checked).",
        "Linted 3 variants:",
        "  robot.urdf.xacro (default arguments)",
        "  robot.urdf.xacro wheels:=18",
        "  robot.urdf.xacro gripper:=false",
        "Read 1 file; 264 findings suppressed (260 by inline comments, 1 by config ignores, "
        "3 by baseline).",
    ]


def test_a_name_with_a_newline_or_an_escape_stays_on_its_line(tmp_path) -> None:
    """A link named `base&#10;::error ...` must not put a GitHub workflow command on a line
    of its own in a CI log, nor send the terminal an escape sequence (a C1 CSI: XML 1.0 has no ESC)."""
    from robotdesc.cli import main

    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="base&#10;::error file=x.py::forged&#155;2J">'
                     '<inertial><mass value="1"/><inertia ixx="-1" ixy="0" ixz="0" iyy="1" '
                     'iyz="0" izz="1"/></inertial></link></robot>\n')
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(["lint", "--no-cache", "-q", str(robot)]) == 1
    text = out.getvalue()
    assert "I103" in text and "base\\n::error file=x.py::forged\\x9b2J" in text
    assert not any(line.startswith("::") for line in text.splitlines())
    assert "\x9b" not in text
