"""Discovery of top-level descriptions in a package or workspace, and config targets with
argument matrices (fixture: tests/fixtures/ci_workspace, two packages)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from robotdesc.config import load_config
from robotdesc.errors import ConfigError, InputError
from robotdesc.linting.targets import description_kind, discover_targets, target_name

WORKSPACE = Path(__file__).resolve().parents[1] / "fixtures" / "ci_workspace"
ARM = WORKSPACE / "src" / "arm_description"
BASE = WORKSPACE / "src" / "base_description"


def names(discovery) -> list[str]:
    return [t.name(str(WORKSPACE)) for t in discovery.targets]


def test_workspace_discovery_finds_robots_skips_libraries_and_expands_the_matrix() -> None:
    found = discover_targets(str(WORKSPACE))
    assert found.directory
    assert names(found) == ["src/arm_description/urdf/arm.urdf.xacro[arm_type=short]",
                            "src/arm_description/urdf/arm.urdf.xacro[arm_type=long]",
                            "src/base_description/urdf/base.urdf"]
    assert sorted(Path(p).name for p in found.libraries) == ["arm_macro.xacro",
                                                            "materials.xacro"]
    long = found.targets[1]
    assert long.args == (("prefix", "arm_"), ("arm_type", "long"))
    assert long.variant == (("arm_type", "long"),)
    assert long.config.path == str(ARM / "robotdesc.toml")
    assert found.targets[2].config.path == str(BASE / "robotdesc.toml")


def test_a_named_file_is_linted_as_given_with_its_config_variants() -> None:
    assert [t.variant for t in discover_targets(str(ARM / "urdf" / "arm.urdf.xacro")).targets] \
        == [(("arm_type", "short"),), (("arm_type", "long"),)]
    library = discover_targets(str(ARM / "urdf" / "arm_macro.xacro"))
    assert [t.variant for t in library.targets] == [()]  # named explicitly: linted


def test_config_targets_replace_discovery_for_the_files_they_govern(tmp_path) -> None:
    package = tmp_path / "pkg"
    shutil.copytree(ARM, package)
    (package / "urdf" / "other.urdf").write_text("<robot name='o'><link name='a'/></robot>")
    found = discover_targets(str(package))
    assert [t.name(str(package)) for t in found.targets] == [
        "urdf/arm.urdf.xacro[arm_type=short]", "urdf/arm.urdf.xacro[arm_type=long]"]
    assert [Path(p).name for p in found.unlisted] == ["other.urdf"]


@pytest.mark.parametrize(("text", "kind"), [
    ("<robot name='r'><link name='a'/></robot>", "robot"),
    ("<robot xmlns:xacro='http://www.ros.org/wiki/xacro'><xacro:macro name='m'/></robot>",
     "library"),
    (("<robot xmlns:xacro='http://www.ros.org/wiki/xacro'><xacro:property name='p' value='1'/>"
     "<material name='grey'/></robot>"), "library"),
    (("<robot xmlns:xacro='http://www.ros.org/wiki/xacro'><xacro:include filename='a.xacro'/>"
     "<xacro:m/></robot>"), "robot"),
    (("<robot xmlns:xacro='http://www.ros.org/wiki/xacro'><xacro:include filename='a.xacro'/>"
     "</robot>"), "robot"),
    (("<robot xmlns:xacro='http://www.ros.org/wiki/xacro'><xacro:if value='1'>"
     "<link name='a'/></xacro:if></robot>"), "robot"),
    (("<robot xmlns:xacro='http://wiki.ros.org/xacro'><xacro:include filename='a.xacro'/>"
     "<xacro:macro name='m'/></robot>"), "library"),
    ("<launch/>", "other"),
    ("<robot><link", "robot"),  # malformed: linted so that the syntax error is reported
])
def test_description_kind(tmp_path, text: str, kind: str) -> None:
    path = tmp_path / "file.xacro"
    path.write_text(text)
    assert description_kind(str(path)) == kind


def test_plain_urdf_with_robot_root_is_a_robot(tmp_path) -> None:
    path = tmp_path / "r.urdf"
    path.write_text("<robot name='r'/>")
    assert description_kind(str(path)) == "robot"


def test_errors_name_the_path(tmp_path) -> None:
    with pytest.raises(InputError, match="no such file"):
        discover_targets(str(tmp_path / "missing"))
    (tmp_path / "lib.xacro").write_text("<robot xmlns:xacro='http://www.ros.org/wiki/xacro'>"
                                        "<xacro:macro name='m'/></robot>")
    with pytest.raises(InputError, match="no robot description"):
        discover_targets(str(tmp_path))


def test_target_config_is_validated(tmp_path) -> None:
    config = tmp_path / "robotdesc.toml"
    config.write_text('[[targets]]\nfile = "missing.urdf"\n')
    with pytest.raises(ConfigError, match="target file 'missing.urdf' does not exist") as info:
        load_config(str(config))
    assert info.value.span.line == 2
    (tmp_path / "r.urdf").write_text("<robot name='r'/>")
    config.write_text('[[targets]]\nfile = "r.urdf"\nmatrix = { a = [] }\n')
    with pytest.raises(ConfigError, match="non-empty list"):
        load_config(str(config))
    config.write_text('[[targets]]\nfile = "r.urdf"\nflavour = 1\n')
    with pytest.raises(ConfigError, match="unknown key 'targets.flavour'"):
        load_config(str(config))
    config.write_text('[[targets]]\nfile = "r.urdf"\nmatrix = { hand = [true, false] }\n')
    (spec,) = load_config(str(config)).targets
    assert spec.matrix == (("hand", ("true", "false")),)


def test_target_name_is_relative_when_below_base(tmp_path) -> None:
    assert target_name(str(tmp_path / "a" / "b.urdf"), (("x", "1"),), str(tmp_path)) == \
        "a/b.urdf[x=1]"
    assert target_name("/elsewhere/b.urdf", (), str(tmp_path)) == "/elsewhere/b.urdf"
