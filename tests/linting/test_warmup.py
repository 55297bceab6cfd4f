"""Importing ahead while the xacro worker expands (robotdesc/linting/warmup.py): the thread
starts only once a worker runs, stops when asked, and a failure in it changes nothing."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from robotdesc.expansion import ExpandOptions, expand_file
from robotdesc.linting.driver import lint_file
from robotdesc.linting import warmup
from robotdesc.linting.warmup import ImportsAhead, lint_imports
from robotdesc.mesh.prefetch import forks_here

XACRO = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="size" value="0.1"/>
  <link name="base"><visual><geometry><box size="${size} 1 1"/></geometry></visual></link>
</robot>
"""


def test_the_thread_starts_only_once_the_worker_runs(tmp_path: Path) -> None:
    (tmp_path / "r.urdf.xacro").write_text(XACRO)
    (tmp_path / "r.urdf").write_text('<robot name="r"><link name="base"/></robot>')
    started: list[str] = []
    options = ExpandOptions(use_cache=False)
    expand_file(tmp_path / "r.urdf", options=options, on_worker_start=lambda: started.append("urdf"))
    assert started == []
    expand_file(tmp_path / "r.urdf.xacro", options=options,
                on_worker_start=lambda: started.append("xacro"))
    assert started == ["xacro"]


def test_a_lint_of_xacro_gives_the_same_findings_with_or_without_the_thread(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "r.urdf.xacro").write_text(XACRO)
    options = ExpandOptions(use_cache=False)
    ahead = lint_file(str(tmp_path / "r.urdf.xacro"), expand_options=options, select=["ALL"])
    monkeypatch.setattr("robotdesc.linting.driver.lint_imports", lambda *_a, **_k: iter(()))
    plain = lint_file(str(tmp_path / "r.urdf.xacro"), expand_options=options, select=["ALL"])
    assert ahead.diagnostics == plain.diagnostics
    assert ahead.diagnostics  # the box has no inertial, no collision, ...


def test_a_failing_import_in_the_thread_fails_again_where_the_lint_imports_it(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "broken_ahead.py").write_text("raise RuntimeError('broken at import')\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    ahead = ImportsAhead(lambda: iter(["no_such_module_anywhere", "broken_ahead", "json"]))
    ahead.start()
    ahead.stop()
    assert "broken_ahead" not in sys.modules
    with pytest.raises(RuntimeError, match="broken at import"):
        __import__("broken_ahead")


def test_a_failing_plan_and_a_stop_before_the_start_are_harmless() -> None:
    def plan():
        yield "json"
        raise ValueError("a plan that fails")

    ahead = ImportsAhead(plan)
    ahead.start()
    ahead.stop()
    never = ImportsAhead(lambda: iter(["json"]))
    never.stop()
    never.start()  # stopped first: it imports nothing
    never.stop()


def test_stop_imports_nothing_more(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "late_ahead.py").write_text("")
    monkeypatch.syspath_prepend(str(tmp_path))
    ahead = ImportsAhead(lambda: iter(["late_ahead"]))
    ahead.stop()
    ahead.start()
    ahead.stop()
    assert "late_ahead" not in sys.modules


def test_what_is_imported_follows_the_selection() -> None:
    structural = list(lint_imports(["J"], (), analyze_meshes=True))
    assert structural == ["robotdesc.model.parse", "robotdesc.rules.catalog"]
    default = list(lint_imports(None, (), analyze_meshes=False))
    assert "robotdesc.mesh.summary" in default and "collada" not in default
    cold = list(lint_imports(None, (), analyze_meshes=True))
    # pycollada last; not where a forked child shares the summaries (it imports it there)
    assert (cold[-1] == "collada") != forks_here()
    assert not any(name.startswith("scipy") for name in cold)  # the hull is numpy's


def test_pycollada_is_imported_ahead_where_no_child_shares_the_summaries(
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(warmup, "forks_here", lambda: False)
    assert list(lint_imports(None, (), analyze_meshes=True))[-1] == "collada"
    monkeypatch.setattr(warmup, "forks_here", lambda: True)
    assert "collada" not in lint_imports(None, (), analyze_meshes=True)
