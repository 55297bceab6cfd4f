"""What a lint does while the xacro worker expands (robotdesc/linting/warmup.py): only then,
never counted against the worker, and a failure in it changes nothing; where a forked child
decides Pinocchio's verdict, this process imports no Pinocchio."""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

import pytest

from robotdesc.expansion import ExpandOptions, expand_file
from robotdesc.forked import forks_here
from robotdesc.linting import warmup
from robotdesc.linting.driver import lint_file
from robotdesc.linting.warmup import import_ahead, lint_imports, pinocchio_in_child

XACRO = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="size" value="0.1"/>
  <link name="base"><visual><geometry><box size="${size} 1 1"/></geometry></visual></link>
</robot>
"""


def test_the_work_runs_only_while_a_worker_expands(tmp_path: Path) -> None:
    (tmp_path / "r.urdf.xacro").write_text(XACRO)
    (tmp_path / "r.urdf").write_text('<robot name="r"><link name="base"/></robot>')
    called: list[str] = []
    options = ExpandOptions(use_cache=False)
    expand_file(tmp_path / "r.urdf", options=options, while_expanding=lambda: called.append("urdf"))
    assert called == []
    expand_file(tmp_path / "r.urdf.xacro", options=options,
                while_expanding=lambda: called.append("xacro"))
    assert called == ["xacro"]


def test_a_slow_wait_is_not_the_workers_time(tmp_path: Path) -> None:
    """The deadline moves by what this process did meanwhile: a worker that answered in time
    is never called too slow."""
    (tmp_path / "r.urdf.xacro").write_text(XACRO)
    options = ExpandOptions(use_cache=False, timeout_s=1.0)
    expanded = expand_file(tmp_path / "r.urdf.xacro", options=options,
                           while_expanding=lambda: time.sleep(1.5))
    assert b"<robot" in expanded.xml


def test_a_lint_of_xacro_gives_the_same_findings_with_or_without_the_work_ahead(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "r.urdf.xacro").write_text(XACRO)
    options = ExpandOptions(use_cache=False)
    ahead = lint_file(str(tmp_path / "r.urdf.xacro"), expand_options=options, select=["ALL"])
    monkeypatch.setattr("robotdesc.linting.driver.lint_imports", lambda *_a, **_k: iter(()))
    monkeypatch.setattr("robotdesc.linting.driver.start_verdict", lambda: None)
    plain = lint_file(str(tmp_path / "r.urdf.xacro"), expand_options=options, select=["ALL"])
    assert ahead.diagnostics == plain.diagnostics
    assert ahead.diagnostics  # the box has no inertial, no collision, ...


def test_a_failing_import_ahead_fails_again_where_the_lint_imports_it(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "broken_ahead.py").write_text("raise RuntimeError('broken at import')\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    import_ahead(iter(["no_such_module_anywhere", "broken_ahead", "json"]))
    assert "broken_ahead" not in sys.modules
    with pytest.raises(RuntimeError, match="broken at import"):
        __import__("broken_ahead")


def test_a_failing_plan_is_harmless() -> None:
    def plan():
        yield "json"
        raise ValueError("a plan that fails")

    import_ahead(plan())


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


def test_pinocchio_is_imported_ahead_only_where_no_child_decides(
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(warmup, "forks_here", lambda: True)
    monkeypatch.setattr(warmup, "verdict_started", lambda: False)
    monkeypatch.setattr(warmup, "more_expected", lambda: False)
    assert "pinocchio" not in lint_imports(None, (), analyze_meshes=True)  # K101 only
    assert "pinocchio" in lint_imports(["K101", "K201"], (), analyze_meshes=True)  # K201: a model
    monkeypatch.setattr(warmup, "more_expected", lambda: True)  # targets follow: here, once
    assert "pinocchio" in lint_imports(None, (), analyze_meshes=True)
    monkeypatch.setattr(warmup, "more_expected", lambda: False)
    monkeypatch.setattr(warmup, "verdict_started", lambda: True)  # a later target: here
    assert "pinocchio" in lint_imports(None, (), analyze_meshes=True)
    monkeypatch.setattr(warmup, "forks_here", lambda: False)
    monkeypatch.setattr(warmup, "verdict_started", lambda: False)
    assert "pinocchio" in lint_imports(None, (), analyze_meshes=True)
    assert not pinocchio_in_child([])


KNEE_XACRO = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="a"/><link name="b"/>
  <joint name="knee" type="revolute"><parent link="a"/><child link="b"/></joint>
</robot>
"""


@pytest.mark.skipif(not forks_here(),
                                 reason="robotdesc forks helper processes on Linux only")
def test_a_cold_lint_asks_a_child_and_imports_no_pinocchio(tmp_path: Path) -> None:
    pytest.importorskip("pinocchio", reason="Pinocchio is the optional [kinematics] extra")
    (tmp_path / "knee.urdf.xacro").write_text(KNEE_XACRO)
    script = (
        "import sys\n"
        "from robotdesc.expansion import ExpandOptions\n"
        "from robotdesc.linting.driver import lint_file\n"
        "import robotdesc.linting.driver as driver\n"
        f"path = {str(tmp_path / 'knee.urdf.xacro')!r}\n"
        "options = ExpandOptions(use_cache=False)\n"
        "child = lint_file(path, expand_options=options)\n"
        "print('pinocchio' in sys.modules)\n"
        "driver.start_verdict = lambda: None\n"
        "here = lint_file(path, expand_options=options)\n"
        "print('pinocchio' in sys.modules, child.diagnostics == here.diagnostics,\n"
        "      'K101' in child.rules_run)\n")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=False,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["False", "True", "True", "True"]
