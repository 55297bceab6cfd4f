"""The package resolver chain: first hit wins, each hit names its source."""

from __future__ import annotations

from pathlib import Path

from robotdesc.expansion.packages import (
    PackageResolver,
    PackageResolverConfig,
    crawl_packages,
    split_package_uri,
    workspace_root,
)

WS = Path(__file__).parent / "fixtures" / "ws"
ROBOT = WS / "src" / "robot_pkg" / "urdf" / "robot.urdf.xacro"


def _package(root: Path, name: str) -> Path:
    folder = root / name
    folder.mkdir(parents=True)
    (folder / "package.xml").write_text(f"<package format='3'><name>{name}</name></package>")
    return folder


def test_enclosing_then_workspace():
    resolver = PackageResolver(PackageResolverConfig(str(ROBOT)))
    assert resolver.find("robot_pkg").source == "enclosing"
    assert resolver.find("arm_pkg").source == "workspace"
    assert resolver.find("nothing_here") is None
    assert workspace_root(WS / "src" / "arm_pkg") == WS


def test_explicit_path_wins_over_workspace(tmp_path):
    other = _package(tmp_path, "arm_pkg")
    resolver = PackageResolver(PackageResolverConfig(str(ROBOT), package_paths=(str(tmp_path),)))
    hit = resolver.find("arm_pkg")
    assert (hit.path, hit.source) == (str(other), "--package-path")


def test_config_map(tmp_path):
    folder = _package(tmp_path, "mapped")
    resolver = PackageResolver(PackageResolverConfig(str(ROBOT), package_map=(("mapped", str(folder)),)))
    assert resolver.find("mapped").source == "config"


def test_ros_package_path_and_ament_prefix(tmp_path):
    ros = _package(tmp_path / "ros", "from_ros")
    share = tmp_path / "prefix" / "share"
    ament = _package(share, "from_ament")
    lone = tmp_path / "lone.urdf.xacro"
    lone.write_text("<robot/>")
    resolver = PackageResolver(PackageResolverConfig(
        str(lone), ros_package_path=str(tmp_path / "ros"), ament_prefix_path=str(tmp_path / "prefix")))
    assert (resolver.find("from_ros").path, resolver.find("from_ros").source) == (str(ros), "ROS_PACKAGE_PATH")
    assert (resolver.find("from_ament").path, resolver.find("from_ament").source) == \
        (str(ament), "AMENT_PREFIX_PATH")


def test_crawl_skips_build_folders_and_nested_packages(tmp_path):
    _package(tmp_path, "top")
    _package(tmp_path / "top", "nested")
    _package(tmp_path / "build", "built")
    assert set(crawl_packages(tmp_path)) == {"top"}


def test_an_install_space_folder_name_is_a_package_name_too(tmp_path):
    """example-robot-data installs share/example-robot-data/ with a package.xml named
    example_robot_descriptions, and its URDFs say package://example-robot-data."""
    share = tmp_path / "prefix" / "share"
    folder = share / "example-robot-data"
    folder.mkdir(parents=True)
    (folder / "package.xml").write_text(
        "<package format='3'><name>example_robot_descriptions</name></package>")
    found = crawl_packages(share)
    assert found == {"example_robot_descriptions": folder, "example-robot-data": folder}
    other = _package(tmp_path / "src", "real_name")
    (tmp_path / "src" / "renamed").mkdir()
    other.rename(tmp_path / "src" / "renamed" / "pkg")  # not under share/: no alias
    assert set(crawl_packages(tmp_path / "src")) == {"real_name"}


def test_split_package_uri():
    assert split_package_uri("package://pkg/meshes/a.stl") == ("pkg", "meshes/a.stl", False)
    assert split_package_uri("package:///pkg/meshes/a.stl") == ("pkg", "meshes/a.stl", True)
    assert split_package_uri("meshes/a.stl") is None
