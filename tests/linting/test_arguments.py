"""Command-line xacro arguments checked before any lint: declared ones found by reading the
file and its includes, an undeclared one a usage error (exit 2) with did-you-mean, arguments
replacing a file's config variants (unless --variants), none for a plain URDF."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from robotdesc.cli import main
from robotdesc.linting.arguments import declared_arguments, one_run_per_file
from robotdesc.linting.targets import LintTarget

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
ENGINEER = Path(__file__).resolve().parents[2] / "robots" / "engineer_description" / "urdf" / \
    "engineer.urdf.xacro"


@pytest.fixture
def package(tmp_path: Path) -> Path:
    """A description with an argument declared in an included file and one read only, and
    a config with two variants."""
    (tmp_path / "parts.xacro").write_text(
        f'<robot {XACRO_NS}>\n  <xacro:arg name="with_gripper" default="true"/>\n</robot>\n')
    (tmp_path / "robot.urdf.xacro").write_text(
        f'<robot name="r" {XACRO_NS}>\n  <xacro:arg name="wheels" default="4"/>\n'
        '  <xacro:include filename="parts.xacro"/>\n'
        '  <link name="base_$(arg wheels)_$(arg suffix)"/>\n</robot>\n')
    (tmp_path / "robotdesc.toml").write_text(
        '[[targets]]\nfile = "robot.urdf.xacro"\nargs = { suffix = "a" }\n\n'
        '[[targets]]\nfile = "robot.urdf.xacro"\nargs = { suffix = "b", wheels = "6" }\n')
    return tmp_path


def test_declared_arguments_follow_includes(package: Path) -> None:
    found = declared_arguments(str(package / "robot.urdf.xacro"))
    assert set(found.names) == {"wheels", "with_gripper", "suffix"}
    assert found.complete and found.xacro


def test_an_include_that_cannot_be_followed_leaves_it_to_the_expansion(tmp_path: Path) -> None:
    (tmp_path / "a.urdf.xacro").write_text(
        f'<robot name="r" {XACRO_NS}><xacro:include filename="${{part}}.xacro"/></robot>')
    assert not declared_arguments(str(tmp_path / "a.urdf.xacro")).complete


def test_an_undeclared_argument_is_a_usage_error_before_any_lint(package: Path, capsys) -> None:
    assert main(["lint", str(package / "robot.urdf.xacro"), "with_griper:=false"]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert "'with_griper' is not declared" in err and "did you mean 'with_gripper'?" in err
    assert "It declares: wheels, suffix, with_gripper." in err


def test_arguments_on_a_plain_urdf_are_a_usage_error(tmp_path: Path, capsys) -> None:
    (tmp_path / "r.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    assert main(["lint", str(tmp_path / "r.urdf"), "x:=1"]) == 2
    assert "is a plain URDF: no xacro arguments apply" in capsys.readouterr().err


def test_cli_arguments_replace_the_config_variants_unless_variants(package: Path,
                                                                   capsys) -> None:
    robot = str(package / "robot.urdf.xacro")
    main(["lint", "--format", "json", robot, "suffix:=c"])
    out, err = capsys.readouterr()
    assert [v["args"] for v in json.loads(out)["summary"]["variants"]] == [{"suffix": "c"}]
    assert "linting once with suffix:=c instead of its config variants" in err
    main(["lint", "--format", "json", "--variants", robot, "suffix:=c"])
    variants = json.loads(capsys.readouterr().out)["summary"]["variants"]
    assert [v["args"] for v in variants] == [{"suffix": "c"}, {"suffix": "c", "wheels": "6"}]


def test_one_run_per_file_keeps_a_single_target_as_is() -> None:
    single = LintTarget("/a.xacro", args=(("x", "1"),))
    pair = [LintTarget("/b.xacro", args=(("y", "1"),)), LintTarget("/b.xacro", args=(("y", "2"),))]
    targets, replaced = one_run_per_file([single, *pair])
    assert targets == [single, LintTarget("/b.xacro")] and replaced == ["/b.xacro"]


def test_the_engineer_names_with_gripper_at_once(capsys) -> None:
    assert main(["lint", str(ENGINEER), "with_griper:=false"]) == 2
    out, err = capsys.readouterr()
    assert out == ""  # no lint ran (benchmarks/bench_cli_arguments.py times it)
    assert "did you mean 'with_gripper'?" in err and "main_track_wheels" in err


def test_bare_robotdesc_lists_the_commands(capsys) -> None:
    assert main([]) == 0
    out = capsys.readouterr().out
    assert all(name in out for name in ("lint", "expand", "collision", "report"))
