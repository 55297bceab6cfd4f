"""`robotdesc lint --fix` / `--diff` over lint targets: lint with the model kept, plan the
fixes, and (for --fix) write them, repeating while a pass still fixes something (a fixed mesh
scale can change an inertia suggestion)."""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from robotdesc.errors import InputError
from robotdesc.expansion import ExpandOptions
from robotdesc.linting.driver import lint_file
from robotdesc.linting.fix.engine import FixOutcome, FixPlan, plan_fixes, write_fixes
from robotdesc.linting.result import LintResult
from robotdesc.linting.targets import LintTarget

log = logging.getLogger(__name__)

#: --fix re-lints and fixes again at most this many times.
MAX_PASSES = 4


@dataclass(frozen=True)
class FixRun:
    """What a --fix or --diff run did.

    Attributes:
        diff: the unified diff of the first pass (--diff prints it).
        outcomes: the fixable findings of the last pass and their fate.
        fixed: how many problems were fixed over all passes (findings fixed by the same
            edits, one macro line over its elements and variants, count once).
        written: the files written; refused: files not written, changed since read.
    """

    diff: str
    outcomes: tuple[FixOutcome, ...]
    fixed: int = 0
    written: tuple[str, ...] = ()
    refused: tuple[str, ...] = ()


def fix_targets(targets: Sequence[LintTarget], *, args: Mapping[str, str] | None = None,
                expand_options: ExpandOptions | None = None,
                select: Sequence[str] | None = None,
                ignore: Sequence[str] = (), unsafe: bool = False, write: bool = True
                ) -> FixRun:
    """Plan (and with `write`, apply) the fixes of every target's findings."""
    first_diff: str | None = None
    fixed = 0
    written: list[str] = []
    refused: list[str] = []
    plan = FixPlan()
    for number in range(MAX_PASSES if write else 1):
        plan = _plan(targets, args, expand_options, select, ignore, unsafe)
        if first_diff is None:
            first_diff = plan.diff()
        if not write or not plan.files:
            break
        done, changed = write_fixes(plan)
        written += [p for p in done if p not in written]
        refused += changed
        fixed += plan.problems_fixed
        log.info("fix pass %d: %d problem(s) fixed in %d file(s)", number + 1,
                 plan.problems_fixed, len(done))
        if changed:
            break
    return FixRun(first_diff or "", plan.outcomes, fixed, tuple(written), tuple(refused))


def _plan(targets: Sequence[LintTarget], args: Mapping[str, str] | None,
          expand_options: ExpandOptions | None, select: Sequence[str] | None,
          ignore: Sequence[str], unsafe: bool) -> FixPlan:
    options = expand_options or ExpandOptions()
    results: list[LintResult] = []
    for target in targets:
        try:
            result = lint_file(target.path, target.config,
                               args={**dict(target.args), **dict(args or {})},
                               expand_options=options, select=select, ignore=ignore)
        except InputError as exc:
            log.info("not fixing %s: %s", target.path, exc)
            continue
        results.append(result)
    return plan_fixes(results, unsafe=unsafe)
