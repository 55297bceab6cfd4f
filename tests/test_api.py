"""The public API in robotdesc/__init__.py: load, expand, lint, __version__."""

from __future__ import annotations

from pathlib import Path

import pytest

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

import robotdesc
from robotdesc.errors import InputError, UsageError

REPO = Path(__file__).resolve().parents[1]
URDF = """<robot name="tiny">
  <link name="base"/>
  <link name="arm"/>
  <joint name="j" type="fixed"><parent link="base"/><child link="nowhere"/></joint>
</robot>
"""


@pytest.fixture
def urdf(tmp_path: Path) -> Path:
    (tmp_path / ".git").mkdir()  # no config above this folder applies
    path = tmp_path / "tiny.urdf"
    path.write_text(URDF)
    return path


def test_version_matches_pyproject() -> None:
    project = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]
    if "version" in project:
        assert robotdesc.__version__ == project["version"]
    else:  # dynamic version read from the package
        assert "version" in project.get("dynamic", [])


def test_load_and_expand(urdf: Path) -> None:
    robot = robotdesc.load(str(urdf))
    assert robot.name == "tiny" and [link.name for link in robot.links] == ["base", "arm"]
    assert robot.joints[0].where.span.line == 4
    expanded = robotdesc.expand(str(urdf))
    assert expanded.source == str(urdf) and b"tiny" in expanded.xml


def test_lint_returns_a_result(urdf: Path) -> None:
    result = robotdesc.lint(str(urdf))
    assert result.diagnostics, "a joint to a missing link must be reported"
    assert any(d.where.span.line == 4 for d in result.diagnostics)
    assert robotdesc.json_report(result)["summary"]["files_checked"] == 1
    assert robotdesc.lint(str(urdf), ignore=["ALL"]).diagnostics == ()


def test_lint_accepts_a_config_path(urdf: Path) -> None:
    config = urdf.parent / "custom.toml"
    config.write_text('ignore = ["ALL"]\n')
    assert robotdesc.lint(str(urdf), config=str(config)).diagnostics == ()


def test_load_bad_input_raises_input_error(tmp_path: Path) -> None:
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot>\n<link>\n")
    with pytest.raises(InputError) as caught:
        robotdesc.load(str(broken))
    assert caught.value.span.path.endswith("broken.urdf")


def test_api_functions_survive_importing_the_subpackages(urdf: Path) -> None:
    import importlib
    import inspect

    importlib.import_module("robotdesc.expansion.worker")
    importlib.import_module("robotdesc.linting.driver")
    assert inspect.isfunction(robotdesc.expand) and inspect.isfunction(robotdesc.lint)
    assert robotdesc.expand(str(urdf)).source == str(urdf)
    assert robotdesc.lint(str(urdf)).target == str(urdf)
    assert "package_paths" in inspect.signature(robotdesc.lint).parameters


def test_mesh_inertia_table_renders_and_serialises() -> None:
    from support import REPO

    table = robotdesc.mesh_inertia(str(REPO / "robots" / "engineer_description" / "urdf"
                                       / "engineer.urdf.xacro"), {"main_track_wheels": "4",
                                                                  "flipper_track_wheels": "4"})
    assert table.source == "collision"
    head = table.row("head_link")
    assert head is not None and head.declared_mass > 0 and head.error is not None and head.error < 0.01
    from robotdesc.report.notebook import html_of

    assert "<table" in html_of(table) and "head_link" in str(table)
    assert table.to_dict()["links"][0]["link"] == table.rows[0].link


def test_a_notebook_shows_results_as_the_reports_tables() -> None:
    """The renderers register with IPython's display system (results know no HTML)."""
    pytest.importorskip("IPython")
    from IPython.core.interactiveshell import InteractiveShell

    from robotdesc.collision import CollisionOptions, CollisionResult
    from robotdesc.model.elements import Robot
    from robotdesc.report import notebook

    shell = InteractiveShell.instance()
    try:
        notebook.register()
        result = CollisionResult(Robot("r"), (), CollisionOptions(), 1.0)
        data, _ = shell.display_formatter.format(result)
        assert data["text/html"] == notebook.html_of(result)
    finally:
        InteractiveShell.clear_instance()


def test_the_api_refuses_what_the_command_line_refuses(urdf: Path) -> None:
    """An unknown selector or inertia source is an error, as on the command line, not a
    silently empty result (held-out)."""
    with pytest.raises(UsageError, match="no rule matches 'ZZZ9'"):
        robotdesc.lint(str(urdf), select=["ZZZ9"])
    with pytest.raises(UsageError, match="ignore"):
        robotdesc.lint(str(urdf), ignore=["NOPE"])
    with pytest.raises(UsageError, match="source must be"):
        robotdesc.mesh_inertia(str(urdf), source="foo")  # type: ignore[arg-type]


def test_an_argument_that_is_no_string_is_a_usage_error(urdf: Path) -> None:
    with pytest.raises(UsageError, match="'hand' must be a string, not bool .*'true'"):
        robotdesc.load(str(urdf), args={"hand": True})  # type: ignore[dict-item]
