"""A config table checked key by key into a `Config`; every error names the file and line."""

from __future__ import annotations

from pathlib import Path

import pytest

from robotdesc.config import load_config
from robotdesc.diagnostics import Severity
from robotdesc.errors import ConfigError

from .sample_rules import RULES, DepthOptions, write


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
    ("[sim]\nseparation = 1\n", "unknown key 'sim.separation'", 2),
    ("[sim]\nseparation-multiplier = { dart = -1 }\n", "must be a positive number", 2),
    ("[sim]\nseparation-multiplier = 2\n", "table of engine = multiplier", 2),
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


def test_sim_separation_multiplier_per_engine(tmp_path: Path) -> None:
    path = write(tmp_path / "robotdesc.toml",
                 "[sim]\nseparation-multiplier = { mujoco = 2.6, dart = 1 }\n")
    sim = load_config(str(path), RULES).sim
    assert sim.separation_multiplier_for("mujoco") == 2.6
    assert sim.separation_multiplier_for("dart") == 1.0
    assert sim.separation_multiplier_for("other") is None
