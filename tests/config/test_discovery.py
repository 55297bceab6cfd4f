"""Which config file applies: the walk up, the VCS root, robotdesc.toml before pyproject.toml."""

from __future__ import annotations

from pathlib import Path

from robotdesc.config import Config, discover_config, find_config_file

from .sample_rules import RULES, write


def test_discovery_walks_up_to_the_nearest_config(tmp_path: Path) -> None:
    write(tmp_path / "pyproject.toml", "[tool.robotdesc]\nignore = ['J']\n")
    nested = write(tmp_path / "pkg" / "urdf" / "robot.urdf", "<robot name='r'/>")
    assert find_config_file(str(nested)) == str(tmp_path / "pyproject.toml")
    assert discover_config(str(nested), RULES).ignore == ("J",)


def test_pyproject_without_robotdesc_table_is_skipped(tmp_path: Path) -> None:
    write(tmp_path / "robotdesc.toml", "ignore = ['S']\n")
    write(tmp_path / "pkg" / "pyproject.toml", "[tool.black]\nline-length = 90\n")
    target = write(tmp_path / "pkg" / "robot.urdf", "<robot name='r'/>")
    assert find_config_file(str(target)) == str(tmp_path / "robotdesc.toml")


def test_robotdesc_toml_wins_over_pyproject_in_the_same_folder(tmp_path: Path) -> None:
    write(tmp_path / "pyproject.toml", "[tool.robotdesc]\nignore = ['J']\n")
    write(tmp_path / "robotdesc.toml", "ignore = ['S']\n")
    assert find_config_file(str(tmp_path / "robot.urdf")) == str(tmp_path / "robotdesc.toml")


def test_walk_stops_at_the_vcs_root(tmp_path: Path) -> None:
    write(tmp_path / "robotdesc.toml", "ignore = ['S']\n")
    (tmp_path / "repo" / ".git").mkdir(parents=True)
    target = write(tmp_path / "repo" / "urdf" / "robot.urdf", "<robot name='r'/>")
    assert find_config_file(str(target)) is None
    assert discover_config(str(target), RULES) == Config()
