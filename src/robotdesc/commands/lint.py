"""`robotdesc lint PATH... [name:=value]`: lint descriptions, report in the chosen format.

Exit codes: 0 no finding at or above --fail-on, 1 findings, 2 an input could not be checked.
The fix options (--fix, --diff, --unsafe-fixes) run through `commands/lint_fix.py`.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import logging
import os
import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, TextIO

from robotdesc.commands.inputs import (
    EXIT_FINDINGS,
    EXIT_INPUT,
    EXIT_OK,
    expand_options,
    split_inputs,
)
from robotdesc.config import load_config
from robotdesc.diagnostics import Severity
from robotdesc.errors import PINOCCHIO_HINT, InputError, UsageError
from robotdesc.kinematics.optional import pinocchio_available
from robotdesc.linting.baseline import (
    apply_baseline,
    baseline_counts,
    read_baseline,
    render_baseline,
)
from robotdesc.linting.inputs import run_inputs
from robotdesc.linting.result import LintFailure, LintResult
from robotdesc.linting.targets import Discovery, LintTarget, discover_targets, target_name
from robotdesc.output import RunInputs, check_output, write_output
from robotdesc.progress import progress_for
from robotdesc.report.formats import FORMAT_NAMES, FORMATS, render_report
from robotdesc.report.statistics import render_statistics_json, render_statistics_text
from robotdesc.report.text import render_failure, render_text, write_text
from robotdesc.rules.select import best_match, check_selectors
from robotdesc.source import Span

if TYPE_CHECKING:
    from robotdesc.expansion import ExpandOptions

log = logging.getLogger(__name__)

Outcome = LintResult | LintFailure


def register(subparsers: Any, *, common: argparse.ArgumentParser,
             expansion: argparse.ArgumentParser) -> None:
    """Add the `lint` subcommand."""
    lint = subparsers.add_parser(
        "lint", parents=[common, expansion], help="lint descriptions",
        description="Lint URDF/xacro files. A directory (package or workspace) is searched "
                    "for top-level descriptions: *.urdf, and xacro files that make a robot "
                    "rather than only define macros; a config's `targets` replace the search.")
    lint.add_argument("inputs", nargs="+", metavar="PATH | name:=value",
                      help="files or directories to lint, and xacro arguments")
    lint.add_argument("--select", action="append", default=[], metavar="CODES",
                      help="only these rules (codes, prefixes like J or J1, names; "
                           "comma-separated, repeatable)")
    lint.add_argument("--ignore", action="append", default=[], metavar="CODES",
                      help="skip these rules (added to the config's ignore)")
    lint.add_argument("--format", choices=FORMAT_NAMES, default="text",
                      help="output format: " + "; ".join(f"{f.name}: {f.summary}"
                                                         for f in FORMATS))
    lint.add_argument("--output-file", "-o", metavar="FILE", help="write the report here")
    lint.add_argument("--fail-on", choices=("error", "warning", "info"),
                      help="lowest severity that makes the exit code 1 (default: config, "
                           "else info: any finding)")
    lint.add_argument("--baseline", metavar="FILE",
                      help="report only findings not recorded in this baseline file")
    lint.add_argument("--write-baseline", metavar="FILE",
                      help="record the current findings in FILE (then report as --baseline)")
    lint.add_argument("--statistics", action="store_true",
                      help="print the number of findings per rule instead of the findings "
                           "(text or json)")
    lint.add_argument("--variants", action="store_true",
                      help="with name:=value arguments, lint every config variant of a file "
                           "with them (default: the arguments replace the variants: one run)")
    lint.add_argument("--jobs", "-j", type=int, default=1, metavar="N",
                      help="lint N targets at once in worker processes (0: one per CPU; "
                           "default: 1)")
    lint.add_argument("--scheduler", metavar="ADDRESS",
                      help="lint the targets on a Dask cluster at ADDRESS (tcp://host:8786), "
                           "or 'local' for one of --jobs processes on this machine; the "
                           "files must be at the same paths on its workers; needs "
                           "robotdesc[dask] (docs/ci.md)")
    lint.add_argument("--fix", action="store_true",
                      help="write the safe fixes of findings into the xacro/URDF sources "
                           "(where the value is a literal), then report what remains")
    lint.add_argument("--diff", action="store_true",
                      help="print the fixes as a unified diff and write nothing")
    lint.add_argument("--unsafe-fixes", action="store_true",
                      help="with --fix or --diff, apply the unsafe fixes too (inertia, "
                           "limits, mesh scale)")
    lint.set_defaults(handler=run_lint)


def run_lint(ns: argparse.Namespace) -> int:
    """The handler: find the targets, (fix,) lint, apply the baseline, report."""
    if ns.statistics and ns.format not in ("text", "json"):
        raise UsageError("--statistics works with --format text or json")
    if ns.jobs < 0:
        raise UsageError("--jobs must be 0 (one per CPU) or positive")
    paths, args = split_inputs(ns.inputs)
    select = selectors(ns.select, "--select") or None
    _note_skipped_kinematics(select)
    ignore = selectors(ns.ignore, "--ignore")
    options = expand_options(ns)
    explicit = load_config(ns.config) if ns.config else None

    targets: list[LintTarget] = []
    failures: list[LintFailure] = []
    for raw in paths:
        try:
            discovery = discover_targets(raw, explicit)
        except InputError as exc:
            failures.append(LintFailure(raw, exc))
            continue
        if discovery.directory:
            _write_discovery(sys.stderr, discovery)
        failures.extend(LintFailure(link, InputError(
            "a symlink whose target lies outside the linted folder; not read", Span(link)))
            for link in discovery.refused)
        targets.extend(discovery.targets)
    targets = _with_cli_arguments(ns, targets, args)
    _check_lint_outputs(ns, targets)
    if ns.fix or ns.diff:
        from robotdesc.commands.lint_fix import run_fixes

        if ns.diff:
            return run_fixes(ns, targets, args, options, select, ignore)
        run_fixes(ns, targets, args, options, select, ignore)
    outcomes = _lint_with_progress(ns, targets, args, options, select, ignore)
    outcomes = [dataclasses.replace(o, args=tuple({**dict(t.args), **args}.items()))
                if isinstance(o, LintResult) else o for t, o in zip(targets, outcomes)]
    results = [o for o in outcomes if isinstance(o, LintResult)]
    failures += [o for o in outcomes if isinstance(o, LintFailure)]
    fail_on = {t.path: Severity.parse(ns.fail_on) if ns.fail_on else t.config.fail_on
               for t in targets}
    inputs = _lint_inputs(ns, targets, results, failures, options)
    results = _apply_baseline(ns, results, inputs)
    failed = any(r.failed(fail_on.get(r.target, Severity.INFO)) for r in results)

    if ns.format == "text":
        for failure in failures:  # path:line:col: error: message, the source, the call chain
            sys.stderr.write(render_failure(LintFailure(failure.target or "robotdesc",
                                                        failure.error)))
    _write_report(ns, results, failures, min(fail_on.values(), default=Severity.INFO), inputs)
    return EXIT_INPUT if failures else EXIT_FINDINGS if failed else EXIT_OK


def _with_cli_arguments(ns: argparse.Namespace, targets: list[LintTarget],
                        args: dict[str, str]) -> list[LintTarget]:
    """Check the command line's xacro arguments before any lint (an undeclared one is a
    usage error), and let them replace a file's config variants unless --variants."""
    if not args:
        return targets
    from robotdesc.linting.arguments import check_cli_arguments, one_run_per_file  # lxml

    check_cli_arguments(targets, args)
    if ns.variants:
        return targets
    targets, replaced = one_run_per_file(targets)
    for path in replaced:
        given = " ".join(f"{name}:={value}" for name, value in args.items())
        sys.stderr.write(f"robotdesc: {target_name(path)}: linting once with {given} instead "
                         "of its config variants (--variants: each variant with them)\n")
    return targets


def _note_skipped_kinematics(select: Sequence[str] | None) -> None:
    """Warn when --select names rules that need Pinocchio and it is not installed (a lint
    that only runs them by default says so with -v)."""
    if not select or pinocchio_available():
        return
    from robotdesc.rules.catalog import all_rules  # every rule module: only when selecting

    chosen = [rule.code for rule in all_rules() if rule.family == "kinematics"
              and best_match(select, rule.code, rule.name) > 1]
    if chosen:
        log.warning("%s skipped: Pinocchio is not installed; %s", ", ".join(chosen),
                    PINOCCHIO_HINT)


def selectors(values: Sequence[str], flag: str) -> list[str]:
    """Comma-separated selectors from repeatable flags, checked against the registry.

    Raises:
        UsageError: a selector matches no rule.
    """
    found = [part.strip() for value in values for part in value.split(",") if part.strip()]
    if found:  # the registry only when there is something to check (a warm lint skips it)
        from robotdesc.rules.catalog import all_rules

        check_selectors(found, all_rules(), flag)
    return found


def _lint_with_progress(ns: argparse.Namespace, targets: list[LintTarget],
                        args: dict[str, str], options: ExpandOptions,
                        select: list[str] | None, ignore: list[str]) -> list[Outcome]:
    """`lint_targets` with progress on stderr: target by target in this process, or as one
    step with worker processes."""
    from robotdesc.linting.parallel import effective_jobs, lint_targets

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
        for number, target in enumerate(targets):
            progress.update(number, detail=target.name())
            outcomes += lint_targets([target], args=args, expand_options=options,
                                     select=select, ignore=ignore, jobs=1)
        return outcomes


def _check_lint_outputs(ns: argparse.Namespace, targets: list[LintTarget]) -> None:
    """Refuse, before any work, an output that is a target, the config or the baseline."""
    known = RunInputs().adding([ns.config, ns.baseline], "a file given to this run")
    known = known.adding([t.path for t in targets], "a description being checked")
    for path in (ns.output_file, ns.write_baseline):
        if path:
            check_output(path, known)


def _lint_inputs(ns: argparse.Namespace, targets: list[LintTarget], results: list[LintResult],
                 failures: list[LintFailure], options: ExpandOptions) -> RunInputs:
    """Every file the lint read (targets, includes, configs, package.xml, meshes, the
    baseline): no output may replace one."""
    inputs = RunInputs().adding([ns.config, ns.baseline], "a file given to this run")
    inputs = inputs.adding([t.path for t in targets] + [f.target for f in failures],
                           "a description being checked")
    for result in results:
        inputs += result.inputs if result.inputs is not None else run_inputs(
            result.target, config_path=result.config_path, expanded=result.expanded,
            robot=result.robot, package_paths=options.package_paths,
            package_map=options.package_map)
    return inputs


def _write_discovery(stream: TextIO, discovery: Discovery) -> None:
    """Say what a directory search found (on stderr: reports stay machine-readable)."""
    def listing(names: list[str]) -> str:
        return ", ".join(names[:8]) + (f", ... ({len(names) - 8} more)" if len(names) > 8
                                       else "")

    base = discovery.path
    names = [t.name(base) for t in discovery.targets]
    text = f"robotdesc: {discovery.path}: linting {len(names)} target(s): {listing(names)}"
    if discovery.libraries:
        text += (f"; skipped {len(discovery.libraries)} macro librar"
                 f"{'y' if len(discovery.libraries) == 1 else 'ies'}")
        log.info("macro libraries: %s",
                 listing([target_name(p, (), base) for p in discovery.libraries]))
    if discovery.fragments:
        text += (f"; skipped {len(discovery.fragments)} file(s) another target includes: "
                 + listing([target_name(p, (), base) for p in discovery.fragments]))
    if discovery.unlisted:
        text += (f"; skipped {len(discovery.unlisted)} file(s) not in their config's targets: "
                 + listing([target_name(p, (), base) for p in discovery.unlisted]))
    stream.write(text + "\n")


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


def _write_report(ns: argparse.Namespace, results: list[LintResult],
                  failures: list[LintFailure], fail_on: Severity, inputs: RunInputs) -> None:
    """Render the report in the chosen format to --output-file or stdout."""
    colour = not ns.output_file and _use_colour(sys.stdout)
    text = _render_report(ns.format, ns.statistics, results, failures, fail_on, colour)
    if text is None:  # coloured text straight to the terminal
        write_text(sys.stdout, results, failures, colour=_use_colour(sys.stdout))
    elif ns.output_file:
        write_output(ns.output_file, text.encode("utf-8"), inputs)
    else:
        sys.stdout.write(text)


def _render_report(fmt: str, statistics: bool, results: list[LintResult],
                   failures: list[LintFailure], fail_on: Severity, colour: bool) -> str | None:
    """The report text (None: text format for a terminal, written by `write_text`)."""
    if statistics:
        return (render_statistics_json if fmt == "json" else render_statistics_text)(results)
    if fmt != "text":
        return render_report(fmt, results, failures, fail_on)
    return None if colour else render_text(results, failures)


def _use_colour(stream: TextIO) -> bool:
    """Colour on a terminal, unless NO_COLOR is set; FORCE_COLOR forces it."""
    if os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    return bool(getattr(stream, "isatty", lambda: False)())
