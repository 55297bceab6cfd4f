"""`robotdesc lint` when the whole-result cache cannot answer every target: fix, lint (here
or in worker processes, or on a Dask cluster), apply the baseline, report. Imported by
`commands/lint.py` only then: a warm lint never pays for the lint machinery."""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import sys
from typing import TYPE_CHECKING

from robotdesc.commands.lint_report import finish, known_inputs, split_outcomes
from robotdesc.expansion import launch
from robotdesc.linting.baseline import (
    apply_baseline,
    baseline_counts,
    read_baseline,
    render_baseline,
)
from robotdesc.linting.inputs import run_inputs
from robotdesc.linting.parallel import effective_jobs, lint_targets
from robotdesc.linting.result import LintFailure, LintResult
from robotdesc.linting.targets import LintTarget
from robotdesc.output import RunInputs, write_output
from robotdesc.progress import progress_for

if TYPE_CHECKING:
    from robotdesc.expansion import ExpandOptions

Outcome = LintResult | LintFailure


def lint_and_report(ns: argparse.Namespace, targets: list[LintTarget],
                    failures: list[LintFailure], args: dict[str, str],
                    options: ExpandOptions, select: list[str] | None,
                    ignore: list[str]) -> int:
    """(Fix,) lint the targets found, apply the baseline, report; the exit code."""
    if ns.fix or ns.diff:
        from robotdesc.commands.lint_fix import run_fixes

        if ns.diff:
            return run_fixes(ns, targets, args, options, select, ignore)
        run_fixes(ns, targets, args, options, select, ignore)
    outcomes = _lint_with_progress(ns, targets, args, options, select, ignore)
    results, failed = split_outcomes(targets, outcomes, args)
    failures = failures + failed
    inputs = known_inputs(ns, targets, failures)
    for result in results:
        inputs += result.inputs if result.inputs is not None else run_inputs(
            result.target, config_path=result.config_path, expanded=result.expanded,
            robot=result.robot, package_paths=options.package_paths,
            package_map=options.package_map)
    results = _apply_baseline(ns, results, inputs)
    return finish(ns, targets, results, failures, inputs)


def _lint_with_progress(ns: argparse.Namespace, targets: list[LintTarget],
                        args: dict[str, str], options: ExpandOptions,
                        select: list[str] | None, ignore: list[str]) -> list[Outcome]:
    """`lint_targets` with progress on stderr: target by target in this process, or as one
    step with worker processes."""
    with progress_for(ns, "lint", total=len(targets), unit="targets") as progress:
        if getattr(ns, "scheduler", None):
            progress.update(0, detail=f"Dask cluster {ns.scheduler}")
            return lint_targets(targets, args=args, expand_options=options, select=select,
                                ignore=ignore, jobs=ns.jobs or 0, scheduler=ns.scheduler,
                                on_done=progress.update)
        if min(effective_jobs(ns.jobs), len(targets)) > 1:
            progress.update(0, detail=f"{effective_jobs(ns.jobs)} worker processes")
            return lint_targets(targets, args=args, expand_options=options, select=select,
                                ignore=ignore, jobs=ns.jobs)
        outcomes: list[Outcome] = []
        # each xacro target's worker starts while the previous target is linted
        launch.expect_more(sum(".xacro" in os.path.basename(t.path) for t in targets) - 1)
        try:
            for number, target in enumerate(targets):
                progress.update(number, detail=target.name())
                outcomes += lint_targets([target], args=args, expand_options=options,
                                         select=select, ignore=ignore, jobs=1)
        finally:
            launch.expect_more(0)
        return outcomes


def _apply_baseline(ns: argparse.Namespace, results: list[LintResult],
                    inputs: RunInputs) -> list[LintResult]:
    """--write-baseline records the findings; --baseline (or the written one) hides them."""
    path = ns.write_baseline or ns.baseline
    if not path:
        return results
    if ns.write_baseline:  # applied from memory: the written file is not read back
        text = render_baseline(results, ns.write_baseline)
        write_output(ns.write_baseline, text.encode("utf-8"), inputs)
        count = sum(len(r.diagnostics) for r in results)
        sys.stderr.write(f"robotdesc: wrote {count} finding(s) to {ns.write_baseline}\n")
        recorded = baseline_counts(json.loads(text), path)
    else:
        recorded = read_baseline(path)
    outcome = apply_baseline(results, recorded, os.path.dirname(os.path.abspath(path)))
    kept = [dataclasses.replace(after, suppressed_by_baseline=after.suppressed_by_baseline
                                + len(before.diagnostics) - len(after.diagnostics))
            for before, after in zip(results, outcome.results)]
    outcome = dataclasses.replace(outcome, results=tuple(kept))
    if outcome.matched or outcome.stale:
        sys.stderr.write(f"robotdesc: {outcome.matched} finding(s) hidden by the baseline "
                         f"{path}" + (f"; {outcome.stale} recorded finding(s) no longer occur "
                                      "(rewrite it with --write-baseline)"
                                      if outcome.stale else "") + "\n")
    return list(outcome.results)
