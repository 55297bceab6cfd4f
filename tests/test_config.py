"""Config discovery (walk up, VCS root, robotdesc.toml before pyproject.toml) and validation."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import pytest

from robotdesc.config import Config, discover_config, find_config_file, load_config
from robotdesc.diagnostics import Severity
from robotdesc.errors import ConfigError
from robotdesc.rules.registry import Rule


@dataclass(frozen=True)
class DepthOptions:
    max_depth: int = 16
    ratio: float = 1.0
    names: tuple[str, ...] = ()
    mode: Literal["fast", "slow"] = "fast"
    limit: float | None = None

    def __post_init__(self) -> None:
        if self.max_depth < 1:
            raise ValueError("max_depth must be at least 1")


def _check(robot, ctx):
    """Does nothing."""
    return ()


RULES = [
    Rule("J101", "revolute-without-limit", "joints", Severity.ERROR, _check),
    Rule("J107", "axis-not-normalised", "joints", Severity.WARNING, _check),
    Rule("S001", "no-root-link", "structure", Severity.ERROR, _check),
    Rule("X101", "deep-macro-recursion", "expansion", Severity.WARNING, _check, DepthOptions),
]


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


def test_full_pyproject_config_is_read(tmp_path: Path) -> None:
    config_file = write(tmp_path / "pyproject.toml", """
[project]
name = "x"
[tool.robotdesc]
select = ["J", "S001"]
ignore = ["axis-not-normalised"]
fail-on = "warning"
[tool.robotdesc.per-file-ignores]
"vendor/*.xacro" = ["S"]
[tool.robotdesc.rules.X101]
max_depth = 8
ratio = 2
names = ["a", "b"]
mode = "slow"
[tool.robotdesc.severity]
J107 = "error"
[tool.robotdesc.packages]
my_pkg = "src/my_pkg"
[tool.robotdesc.args]
prefix = "left_"
use_sim = true
""")
    config = load_config(str(config_file), RULES)
    assert config.path == str(config_file)
    assert config.select == ("J", "S001")
    assert config.ignore == ("axis-not-normalised",)
    assert config.fail_on is Severity.WARNING
    assert config.per_file_ignores == (("vendor/*.xacro", ("S",)),)
    assert config.options_for("X101") == DepthOptions(max_depth=8, ratio=2.0, names=("a", "b"),
                                                      mode="slow")
    assert isinstance(config.options_for("X101").ratio, float)
    assert config.severity_for("J107", Severity.WARNING) is Severity.ERROR
    assert config.severity_for("J101", Severity.ERROR) is Severity.ERROR
    assert config.packages == (("my_pkg", str(tmp_path / "src" / "my_pkg")),)
    assert config.args == (("prefix", "left_"), ("use_sim", "true"))


def test_defaults_when_table_is_empty(tmp_path: Path) -> None:
    config = load_config(str(write(tmp_path / "robotdesc.toml", "")), RULES)
    assert config.select is None and config.ignore == ()
    assert config.fail_on is Severity.INFO
    assert config.options_for("X101") is None


def test_rule_options_may_be_keyed_by_rule_name(tmp_path: Path) -> None:
    path = write(tmp_path / "robotdesc.toml", "[rules.deep-macro-recursion]\nmax_depth = 4\n")
    assert load_config(str(path), RULES).options_for("X101").max_depth == 4


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


@pytest.mark.parametrize("text, fragment, line", [
    ("selct = ['J']\n", "unknown key 'selct'", 1),
    ("select = ['Q9']\n", "names no known rule: 'Q9'", 1),
    ("ignore = 'J101'\nfail-on = 'fatal'\n", "unknown severity 'fatal'", 2),
    ("[severity]\nJ999 = 'error'\n", "'severity.J999': no rule", 2),
    ("[rules.X101]\nmax_dept = 3\n", "has no option 'max_dept'", 2),
    ("[rules.X101]\nmax_depth = '3'\n", "expected an integer", 2),
    ("[rules.X101]\nmax_depth = true\n", "expected an integer", 2),
    ("[rules.X101]\nmode = 'medium'\n", "expected one of", 2),
    ("[rules.X101]\nmax_depth = 0\n", "max_depth must be at least 1", 1),
    ("[rules.J101]\nanything = 1\n", "J101 (revolute-without-limit) has no options", 1),
    ("select = [\n", "invalid TOML", 2),
])
def test_invalid_config_names_file_and_line(tmp_path: Path, text: str, fragment: str,
                                            line: int) -> None:
    path = write(tmp_path / "robotdesc.toml", text)
    with pytest.raises(ConfigError) as caught:
        load_config(str(path), RULES)
    assert fragment in caught.value.message
    assert caught.value.span.path == str(path)
    assert caught.value.span.line == line


def test_invalid_pyproject_key_is_reported_with_its_table(tmp_path: Path) -> None:
    path = write(tmp_path / "pyproject.toml", "[project]\nname='x'\n\n[tool.robotdesc]\nfoo = 1\n")
    with pytest.raises(ConfigError, match=r"unknown key 'tool\.robotdesc\.foo'") as caught:
        load_config(str(path), RULES)
    assert caught.value.span.line == 5
