"""Start-up: the commands that read no description import only what they need (issue 31).

Each command line runs in a fresh interpreter, which then lists the modules it imported. The
modules below cost most of the start-up (numpy and trimesh alone are hundreds of ms); a change
that pulls one of them back in fails here, whatever the machine's speed. The wall times, against
the bare interpreter, are measured by benchmarks/bench_startup.py.
"""

from __future__ import annotations

import json
import os
import subprocess
import time
import sys
from pathlib import Path

import pytest

from robotdesc.rules.catalog import all_rules
from robotdesc.rules.index import read_index

SRC = Path(__file__).resolve().parents[1] / "src"

#: Never imported by `--version`, `--help`, `rules`, `rule CODE`.
HEAVY = ("numpy", "trimesh", "lxml", "rich", "xacro", "yaml", "pygls", "robotdesc.linting",
         "robotdesc.rules.catalog", "robotdesc.rules.registry", "robotdesc.expansion",
         "robotdesc.model", "robotdesc.mesh", "robotdesc.config", "robotdesc.report.text")
#: Not imported by `--version` and `--help` either (the failure path's classes and
#: `dataclasses` under them).
ALSO_NOT_FOR_VERSION = ("dataclasses", "robotdesc.errors", "robotdesc.rules")

PROBE = """
import contextlib, io, json, sys
from robotdesc.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    code = main(sys.argv[1:])
sys.stderr.write(json.dumps({"code": code, "modules": sorted(sys.modules)}))
"""


def _imported(*words: str, env: dict[str, str] | None = None) -> set[str]:
    done = subprocess.run([sys.executable, "-c", PROBE, *words], capture_output=True,
                          text=True, env=dict(env or os.environ, PYTHONPATH=str(SRC)),
                          check=False)
    report = json.loads(done.stderr.strip().splitlines()[-1])
    assert report["code"] == 0, done.stderr
    return set(report["modules"])


def _offending(modules: set[str], forbidden: tuple[str, ...]) -> list[str]:
    return sorted(m for m in modules if any(m == f or m.startswith(f + ".") for f in forbidden))


@pytest.mark.parametrize("words", [["--version"], ["--help"]], ids=" ".join)
def test_version_and_help_import_no_command(words: list[str]) -> None:
    modules = _imported(*words)
    assert _offending(modules, HEAVY + ALSO_NOT_FOR_VERSION) == []
    assert not [m for m in modules if m.startswith("robotdesc.commands.")
                and m != "robotdesc.commands.exit_codes"]


@pytest.mark.parametrize("words", [["rules"], ["rule", "J101"], ["rule", "missing-joint-limit"]],
                         ids=" ".join)
def test_rules_and_rule_read_the_index_not_the_rule_modules(words: list[str]) -> None:
    assert read_index() is not None, "the rule index is out of date (see test_rule_docs.py)"
    assert _offending(_imported(*words), HEAVY) == []


def test_the_index_answers_as_the_registry() -> None:
    index = read_index()
    assert index is not None
    assert [row[0] for row in index.rows] == [r.code for r in all_rules()]
    for rule_ in all_rules():
        assert index.find(rule_.code.lower()) == index.find(rule_.name) == index.help[rule_.code]


def test_an_index_of_other_sources_is_not_used(tmp_path: Path) -> None:
    stale = tmp_path / "index.json"
    stale.write_text(json.dumps({"sources": "0" * 64, "rows": [], "help": {}}))
    assert read_index(str(stale)) is None
    for junk in ("[]", "{", json.dumps({"sources": None})):
        stale.write_text(junk)
        assert read_index(str(stale)) is None


#: Not imported by a lint answered from the result cache (nothing is expanded or checked).
#: Nor the lint machinery: `commands/lint.py` asks the cache before importing it.
NOT_FOR_A_WARM_LINT = ("numpy", "trimesh", "lxml", "xacro", "rich", "asyncio",
                       "multiprocessing", "robotdesc.rules.catalog", "robotdesc.model.parse",
                       "robotdesc.expansion.runner", "robotdesc.commands.lint_run",
                       "robotdesc.linting.parallel", "robotdesc.linting.driver",
                       "robotdesc.linting.inputs", "robotdesc.linting.baseline",
                       "robotdesc.model.elements", "robotdesc.mesh.locate",
                       "robotdesc.mesh.context")


def test_a_warm_lint_reads_the_result_cache_and_imports_no_checker(tmp_path: Path) -> None:
    robot = tmp_path / "r.urdf"
    robot.write_text("<robot name='r'><link name='a'><inertial><mass value='1'/><inertia "
                     "ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/></inertial></link>"
                     "</robot>")
    os.utime(robot, ns=(1_600_000_000 * 10**9,) * 2)
    env = dict(os.environ, ROBOTDESC_CACHE_DIR=str(tmp_path / "cache"))
    _imported("lint", "-q", str(robot), env=env)  # cold: fills the cache
    assert _offending(_imported("lint", "-q", str(robot), env=env), NOT_FOR_A_WARM_LINT) == []


#: Not imported by the replay of an unchanged lint either: neither the argument parser nor
#: the lint command, the result cache or the config schema (`commands/lint_replay.py`).
NOT_FOR_A_REPLAY = NOT_FOR_A_WARM_LINT + (
    "argparse", "robotdesc.commands.lint", "robotdesc.linting", "robotdesc.config.schema",
    "robotdesc.config.validate", "robotdesc.expansion", "robotdesc.report")


def test_a_third_identical_lint_is_a_replay_that_imports_no_lint_module(
        tmp_path: Path) -> None:
    robot = tmp_path / "r.urdf"
    robot.write_text("<robot name='r'><link name='a'><inertial><mass value='1'/><inertia "
                     "ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/></inertial></link>"
                     "</robot>")
    written = time.time()
    env = dict(os.environ, ROBOTDESC_CACHE_DIR=str(tmp_path / "cache"))
    _imported("lint", "-q", str(robot), env=env)  # cold: fills the result cache
    time.sleep(max(0.0, written + 2.2 - time.time()))  # the file settles (SETTLE_NS)
    _imported("lint", "-q", str(robot), env=env)  # from the result cache: recorded
    assert list((tmp_path / "cache" / "replay").rglob("*.json"))
    assert _offending(_imported("lint", "-q", str(robot), env=env), NOT_FOR_A_REPLAY) == []


FRONT_PROBE = """
import json, os, sys
import robotdesc.expansion.runner as runner

def sent(*args, **kwargs):  # the job is about to be sent: what has been imported by now
    sys.stderr.write(json.dumps(sorted(sys.modules)))
    sys.stderr.flush()
    os._exit(0)

runner.exchange = sent
from robotdesc.cli import main
main(sys.argv[1:])
"""


@pytest.mark.parametrize("how", ["flags", "config"])
def test_a_selection_is_checked_without_the_rule_modules(tmp_path: Path, how: str) -> None:
    """`--select`/`--ignore` and a config's selectors are checked against the rule index: a
    cold lint imports the rule modules while the worker expands, not before its job."""
    (tmp_path / "r.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a"/></robot>')
    words = ["lint", "--no-cache", str(tmp_path / "r.urdf.xacro")]
    if how == "flags":
        words += ["--select", "J,S,moving-link-without-inertial", "--ignore", "J101"]
    else:
        (tmp_path / "robotdesc.toml").write_text(
            'select = ["J", "S1"]\nignore = ["J101"]\n[per-file-ignores]\n"*.xacro" = ["S2"]\n')
    done = subprocess.run([sys.executable, "-c", FRONT_PROBE, *words], capture_output=True,
                          text=True, cwd=tmp_path, env=dict(os.environ, PYTHONPATH=str(SRC)),
                          check=False, timeout=60)
    modules = json.loads(done.stderr.strip().splitlines()[-1])
    assert "robotdesc.rules.catalog" not in modules, done.stderr[-2000:]
    bad = subprocess.run([sys.executable, "-m", "robotdesc", *words[:3], "--select", "Q9"],
                         capture_output=True, text=True, cwd=tmp_path, check=False,
                         env=dict(os.environ, PYTHONPATH=str(SRC)), timeout=60)
    assert bad.returncode == 2 and "no rule matches 'Q9'" in bad.stderr
