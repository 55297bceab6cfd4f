"""Inputs and snapshot files shared by the CI formatter tests (SARIF, JUnit, GitHub, GitLab).

The sample (report_samples.build_sample) has a finding inside a macro body in an included
file (with two call sites), a finding in the top file, one without a location, and a file
that could not be checked. Here a matrix variant of the same target is added, and rule
descriptors with fixed documentation, so that the snapshots do not change when the registry
grows. Set UPDATE_SNAPSHOTS=1 to rewrite the snapshot files after an intended change.
"""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path

from robotdesc.diagnostics import Severity
from robotdesc.rules.registry import Rule

from .report_samples import build_sample

DATA = Path(__file__).resolve().parent / "data"


def _limit_doc(robot, ctx):  # pragma: no cover - never run, only documented
    """Finds a revolute joint without a `<limit>`.

    Why is this bad?
    A revolute joint needs position, effort and velocity limits.

    Example
    Add `<limit lower="-1" upper="1" effort="1" velocity="1"/>`.
    """
    return ()


def _clash_doc(robot, ctx):  # pragma: no cover
    """Finds links whose names clash."""
    return ()


RULES = [
    Rule("J101", "revolute-without-limit", "joints", Severity.ERROR, _limit_doc),
    Rule("S003", "link-name-case-clash", "structure", Severity.WARNING, _clash_doc),
]


def build_ci_sample(tmp_path: Path):
    """(results, failures, root): the report sample plus a variant of its target."""
    results, failures, root = build_sample(tmp_path)
    variant = dataclasses.replace(results[0], diagnostics=results[0].diagnostics[:1],
                                  variant=(("side", "left"),), rules_run=("J101",))
    first = dataclasses.replace(results[0], rules_run=("J101", "S003", "X001"))
    return [first, variant], failures, root


def normalise(text: str, root: Path) -> str:
    """Replace the temporary directory and the version by placeholders."""
    from robotdesc import __version__

    text = text.replace(root.as_uri(), "file:///ROOT").replace(str(root), "/ROOT")
    return text.replace(f'"{__version__}"', '"VERSION"')


def check_snapshot(name: str, text: str) -> None:
    """Compare with tests/report/data/NAME (rewritten when UPDATE_SNAPSHOTS is set)."""
    path = DATA / name
    if os.environ.get("UPDATE_SNAPSHOTS"):
        path.write_text(text, encoding="utf-8")
    assert path.is_file(), f"no snapshot {path}; run with UPDATE_SNAPSHOTS=1 once"
    assert text == path.read_text(encoding="utf-8")
