"""The one edit engine: conflicts between fixes, only values that change, idempotence,
refusal of a file changed since it was read, atomic writes."""

from __future__ import annotations

from pathlib import Path

import pytest
from linting.test_fix import make_package

from robotdesc.edit.engine import apply_fixes, resolve_conflicts, write_changes
from robotdesc.edit.fix import Edit, Fix
from robotdesc.edit.values import SIX_DIGITS, merged_value
from robotdesc.linting.driver import lint_file
from robotdesc.linting.fix import plan_fixes, write_fixes


@pytest.fixture(autouse=True)
def _own_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", str(tmp_path / "cache"))


def test_different_values_at_one_location_refuse_both(tmp_path: Path) -> None:
    path = str(tmp_path / "a.urdf")
    fixes = resolve_conflicts([Fix((Edit(path, 3, 5, "x", 1),)), Fix((Edit(path, 3, 5, "y", 1),)),
                               Fix((Edit(path, 9, 9, "z", 2),))])
    assert [f.applicable for f in fixes] == [False, False, True]
    assert fixes[0].reason == "fixes ask different values at a.urdf:1"


def test_overlapping_edits_refuse_the_later_fix(tmp_path: Path) -> None:
    path = str(tmp_path / "a.urdf")
    fixes = resolve_conflicts([Fix((Edit(path, 0, 6, "abc"),)), Fix((Edit(path, 4, 8, "d"),))])
    assert [f.applicable for f in fixes] == [True, False]
    assert fixes[1].reason.startswith("overlaps another fix's edit")


def test_the_same_edit_asked_twice_is_applied_once(tmp_path: Path) -> None:
    path = str(tmp_path / "a.urdf")
    edit = Edit(path, 2, 3, "X")
    fixes = resolve_conflicts([Fix((edit,)), Fix((edit,))])
    [change] = apply_fixes(fixes, {path: b"abcdef"})
    assert change.after == b"abXdef"


def test_changed_file_is_refused_and_others_written(tmp_path: Path) -> None:
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_bytes(b"one"), b.write_bytes(b"two")
    changes = apply_fixes([Fix((Edit(str(a), 0, 3, "1"), Edit(str(b), 0, 3, "2")))],
                          {str(a): b"one", str(b): b"two"})
    b.write_bytes(b"TWO")
    assert write_changes(changes) == ([str(a)], [str(b)])
    assert a.read_bytes() == b"1" and b.read_bytes() == b"TWO"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt", "b.txt"]  # no temporary


@pytest.mark.parametrize(("old", "new", "six_digits", "written"), [
    ("0.0842292088 8.64389281e-05 0.00457857104", "0.0842292 8.64389e-05 0.00457857", True,
     None),  # equal within the suggestion's six digits: not rewritten
    ("0.0842292088 8.64389281e-05 0.00457857104", "0.0842292 8.64389e-05 0.005", True,
     "0.0842292088 8.64389281e-05 0.005"),  # only the number that changes
    ("0 2 0", "0 1 0", False, "0 1 0"),
    ("1.0", "1", False, None),
    ("0.0842292088", "0.0842292", False, "0.0842292"),  # a precise fix is written as asked
])
def test_only_values_that_change_are_rewritten(old, new, six_digits, written) -> None:
    tolerance = SIX_DIGITS if six_digits else 1e-9
    assert merged_value(old, new, tolerance=tolerance) == written


def test_fixing_again_changes_nothing(tmp_path: Path) -> None:
    path = make_package(tmp_path)
    passes = []
    while (plan := plan_fixes([lint_file(str(path))], unsafe=True)).files:
        assert write_fixes(plan)[0] == [str(path)] and len(passes) < 3
        passes.append(plan.diff())
    # a scaled mesh can change what the inertia rules suggest: --fix runs passes until none
    assert 1 <= len(passes) <= 2 and 'scale="0.001 0.001 0.001"' in passes[0]
    fixed = path.read_bytes()
    assert plan_fixes([lint_file(str(path))], unsafe=True).files == ()
    assert path.read_bytes() == fixed
