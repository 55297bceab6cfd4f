"""Folder lints pick real robots (issue 13, item 6): property/macro files that include others
but make no link are not targets, an empty `<robot/>` is skipped with a note, a `.urdf`
written in xacro is judged as xacro, and the packages of the linted folder are found
without workspace markers."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import pytest

from robotdesc import cli
from robotdesc.linting.targets import description_kind, discover_targets, is_placeholder

XACRO = "xmlns:xacro='http://www.ros.org/wiki/xacro'"


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


def package(folder: Path, name: str) -> Path:
    write(folder / "package.xml", f"<package format='3'><name>{name}</name></package>")
    return folder


# --- files that make no link -------------------------------------------------------------


def test_properties_file_that_includes_properties_is_a_library(tmp_path) -> None:
    write(tmp_path / "common.xacro", f"<robot {XACRO}><xacro:property name='a' value='1'/>"
                                     "</robot>")
    constants = write(tmp_path / "calibration_constants.urdf.xacro",
                      f"<robot {XACRO}><xacro:include filename='common.xacro'/>"
                      "<xacro:property name='cal_x' value='0.01'/></robot>")
    assert description_kind(str(constants)) == "library"


def test_file_that_includes_a_robot_body_is_a_robot(tmp_path) -> None:
    write(tmp_path / "body.xacro", f"<robot {XACRO}><link name='base'/></robot>")
    top = write(tmp_path / "robot.urdf.xacro",
                f"<robot name='r' {XACRO}><xacro:include filename='body.xacro'/></robot>")
    assert description_kind(str(top)) == "robot"


def test_includes_are_followed_through_find_of_a_package_in_the_folder(tmp_path) -> None:
    common = package(tmp_path / "common" / "common_description", "common_description")
    write(common / "urdf" / "props.xacro", f"<robot {XACRO}><xacro:arg name='x'/></robot>")
    write(common / "urdf" / "body.xacro", f"<robot {XACRO}><xacro:m/></robot>")
    lib = write(tmp_path / "a" / "lib.xacro", f"<robot {XACRO}><xacro:include filename="
                "'$(find common_description)/urdf/props.xacro'/></robot>")
    top = write(tmp_path / "a" / "top.xacro", f"<robot {XACRO}><xacro:include filename="
                "'$(find common_description)/urdf/body.xacro'/></robot>")
    packages = {"common_description": str(common)}
    assert description_kind(str(lib), packages) == "library"
    assert description_kind(str(top), packages) == "robot"


@pytest.mark.parametrize("filename", ["$(arg body)", "$(find unknown_pkg)/body.xacro",
                                      "${prefix}body.xacro", "missing.xacro"])
def test_an_include_that_cannot_be_followed_counts_as_a_robot(tmp_path, filename) -> None:
    top = write(tmp_path / "top.urdf.xacro",
                f"<robot {XACRO}><xacro:include filename='{filename}'/></robot>")
    assert description_kind(str(top)) == "robot"


def test_include_cycles_end(tmp_path) -> None:
    write(tmp_path / "a.xacro", f"<robot {XACRO}><xacro:include filename='b.xacro'/></robot>")
    write(tmp_path / "b.xacro", f"<robot {XACRO}><xacro:include filename='a.xacro'/></robot>")
    assert description_kind(str(tmp_path / "a.xacro")) == "library"


# --- fragments other files include ------------------------------------------------------


def test_files_another_description_includes_are_fragments_not_targets(tmp_path) -> None:
    """TALOS and the Shadow hand: `talos_full_common.urdf.xacro` (included by the robots),
    `${side}_arm.transmissions.urdf.xacro` (included inside a macro of a library) and a
    parameter file a library includes make links or evaluate parameters of their includer;
    linted alone they fail. A model picked by `$(arg model).urdf.xacro` stays a target."""
    pkg = package(tmp_path / "talos_description", "talos_description")
    write(pkg / "urdf" / "common.urdf.xacro", f"<robot {XACRO}><link name='torso'/></robot>")
    for side in ("left", "right"):
        write(pkg / "urdf" / f"{side}_arm.transmissions.urdf.xacro",
              f"<robot {XACRO}><link name='${{name}}_t'/></robot>")
    write(pkg / "urdf" / "arm.urdf.xacro", f"<robot {XACRO}><xacro:macro name='arm' "
          "params='side'><xacro:include filename='$(find talos_description)/urdf/"
          "${side}_arm.transmissions.urdf.xacro'/></xacro:macro></robot>")
    write(pkg / "robots" / "full.urdf.xacro", f"<robot name='t' {XACRO}><xacro:include "
          "filename='$(find talos_description)/urdf/common.urdf.xacro'/>"
          "<xacro:include filename='../urdf/arm.urdf.xacro'/><xacro:arm side='left'/></robot>")
    write(pkg / "robots" / "any.urdf.xacro", f"<robot name='a' {XACRO}><xacro:include "
          "filename='$(arg model).urdf.xacro'/></robot>")
    write(pkg / "robots" / "model_a.urdf.xacro", f"<robot {XACRO}><link name='a'/></robot>")
    found = discover_targets(str(pkg))
    assert sorted(Path(t.path).name for t in found.targets) == [
        "any.urdf.xacro", "full.urdf.xacro", "model_a.urdf.xacro"]
    assert sorted(Path(f).name for f in found.fragments) == [
        "common.urdf.xacro", "left_arm.transmissions.urdf.xacro",
        "right_arm.transmissions.urdf.xacro"]


def test_files_that_only_include_each_other_stay_targets(tmp_path) -> None:
    write(tmp_path / "a.urdf.xacro", f"<robot {XACRO}><link name='a'/>"
          "<xacro:include filename='b.urdf.xacro'/></robot>")
    write(tmp_path / "b.urdf.xacro", f"<robot {XACRO}><link name='b'/>"
          "<xacro:include filename='a.urdf.xacro'/></robot>")
    found = discover_targets(str(tmp_path))
    assert sorted(Path(t.path).name for t in found.targets) == ["a.urdf.xacro", "b.urdf.xacro"]


# --- empty placeholders ------------------------------------------------------------------


@pytest.mark.parametrize("text", ["<robot/>", ("<robot name='placeholder'>\n  <!-- later -->\n"
                                                "</robot>"), f"<robot {XACRO}/>"])
def test_an_empty_robot_is_a_placeholder(tmp_path, text: str) -> None:
    for name in ("p.urdf", "p.urdf.xacro"):
        assert is_placeholder(str(write(tmp_path / name, text)))
    assert not is_placeholder(str(write(tmp_path / "r.urdf", "<robot><link name='a'/></robot>")))


def test_folder_lint_skips_a_placeholder_with_a_note(tmp_path, caplog, capsys) -> None:
    write(tmp_path / "urdf" / "empty.urdf", "<robot/>\n")
    write(tmp_path / "urdf" / "arm.urdf", "<robot name='arm'><link name='base'/></robot>\n")
    with caplog.at_level(logging.WARNING, logger="robotdesc"):
        found = discover_targets(str(tmp_path))
    assert [Path(t.path).name for t in found.targets] == ["arm.urdf"]
    assert [Path(p).name for p in found.placeholders] == ["empty.urdf"]
    assert "skipped urdf/empty.urdf: an empty <robot/> placeholder" in caplog.text
    assert cli.main(["lint", str(tmp_path), "--format", "json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert "empty.urdf" not in json.dumps(report)


def test_a_folder_of_placeholders_only_is_not_an_input_error(tmp_path) -> None:
    write(tmp_path / "empty.urdf", "<robot/>")
    found = discover_targets(str(tmp_path))
    assert found.targets == () and len(found.placeholders) == 1


def test_a_placeholder_named_explicitly_is_linted(tmp_path) -> None:
    path = write(tmp_path / "empty.urdf", "<robot/>")
    assert [t.path for t in discover_targets(str(path)).targets] == [str(path)]


# --- .urdf files written in xacro --------------------------------------------------------


def test_urdf_named_macro_library_is_a_library(tmp_path) -> None:
    path = write(tmp_path / "wheel.urdf", f"<robot {XACRO}><xacro:macro name='wheel' "
                                          "params='n'><link name='${n}'/></xacro:macro></robot>")
    assert description_kind(str(path)) == "library"
    write(tmp_path / "robot.urdf", "<robot name='r'><link name='base'/></robot>")
    found = discover_targets(str(tmp_path))
    assert [Path(t.path).name for t in found.targets] == ["robot.urdf"]
    assert [Path(p).name for p in found.libraries] == ["wheel.urdf"]


def test_urdf_with_only_a_declared_xacro_namespace_is_a_robot(tmp_path) -> None:
    path = write(tmp_path / "r.urdf", f"<robot name='r' {XACRO}><link name='a'/></robot>")
    assert description_kind(str(path)) == "robot"


def test_urdf_with_substitutions_is_one_clear_finding_not_exit_2(tmp_path, capsys) -> None:
    write(tmp_path / "snippet.urdf",
          f"<robot name='s' {XACRO}>\n<link name='a'>\n<visual><geometry>"
          "<box size='${size} 1 1'/></geometry></visual></link>\n</robot>\n")
    code = cli.main(["lint", str(tmp_path), "--select", "X201", "--format", "json"])
    assert code == 1
    report = json.loads(capsys.readouterr().out)
    text = json.dumps(report)
    assert text.count('"X201"') == 1 and "*.urdf.xacro" in text


# --- packages of the linted folder -------------------------------------------------------


def test_packages_of_the_folder_are_given_to_its_targets(tmp_path) -> None:
    arm = package(tmp_path / "robots" / "arm_description", "arm_description")
    common = package(tmp_path / "shared" / "common_description", "common_description")
    write(arm / "urdf" / "arm.urdf", "<robot name='arm'><link name='base'/></robot>")
    found = discover_targets(str(tmp_path))
    assert dict(found.packages) == {"arm_description": str(arm),
                                    "common_description": str(common)}
    (target,) = found.targets
    # the file's own package is left to the resolver's "enclosing" step
    assert target.config.packages == (("common_description", str(common)),)


def test_config_packages_come_first(tmp_path) -> None:
    own = package(tmp_path / "vendor" / "common_description", "common_description")
    package(tmp_path / "shared" / "common_description", "common_description")
    write(tmp_path / "robotdesc.toml",
          '[packages]\ncommon_description = "vendor/common_description"\n')
    write(tmp_path / "arm.urdf", "<robot name='arm'><link name='base'/></robot>")
    (target,) = discover_targets(str(tmp_path)).targets
    assert target.config.packages[0] == ("common_description", str(own))
    assert [name for name, _ in target.config.packages] == ["common_description"]


def test_folder_lint_resolves_packages_without_workspace_markers(tmp_path, capsys) -> None:
    """No .git, no src/, no colcon files: the sibling package is found because it is under
    the linted folder (before, the workspace guess stopped at robots/)."""
    common = package(tmp_path / "shared" / "common_description", "common_description")
    write(common / "urdf" / "base.xacro",
          f"<robot {XACRO}><xacro:macro name='base'><link name='base'/></xacro:macro></robot>")
    arm = package(tmp_path / "robots" / "arm_description", "arm_description")
    write(arm / "urdf" / "arm.urdf.xacro",
          f"<robot name='arm' {XACRO}>"
          "<xacro:include filename='$(find common_description)/urdf/base.xacro'/>"
          "<xacro:base/></robot>")
    code = cli.main(["lint", str(tmp_path), "--no-cache", "--select", "S", "--format", "json"])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    assert "1 target(s): robots/arm_description/urdf/arm.urdf.xacro" in captured.err


def test_an_unprefixed_include_makes_a_target_whose_lint_says_why(tmp_path, capsys) -> None:
    """NAO's nao_robot_v4.urdf.xacro: `<include>` without `xacro:` (xacro 1 took it, xacro 2
    leaves it as is). The folder lint picks it, and S201 names the missing prefix."""
    write(tmp_path / "body.xacro", f"<robot {XACRO}><link name='torso'/></robot>")
    top = write(tmp_path / "nao_robot_v4.urdf.xacro",
                f"<robot name='nao' {XACRO}>\n  <include filename='body.xacro'/>\n</robot>")
    assert description_kind(str(top)) == "robot"
    found = discover_targets(str(tmp_path))
    assert [Path(t.path).name for t in found.targets] == ["nao_robot_v4.urdf.xacro"]
    assert cli.main(["lint", str(top), "--no-cache", "--select", "S201", "--format",
                     "json"]) == 1
    [s201] = json.loads(capsys.readouterr().out)["diagnostics"]
    assert s201["line"] == 2 and "write <xacro:include>" in s201["message"]
