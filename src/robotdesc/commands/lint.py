"""`robotdesc lint PATH... [name:=value]`: lint descriptions, report in the chosen format.

Exit codes: 0 no finding at or above --fail-on, 1 findings, 2 an input could not be checked.
A lint whose every target the whole-result cache answers is read and reported here, importing
none of the lint machinery (no expansion, parse or rule module: tests/test_startup.py); any
other lint, and the fix options (--fix, --diff, --unsafe-fixes), run through
`commands/lint_run.py`.
"""

from __future__ import annotations

import argparse
import logging
import os
import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from robotdesc.commands.inputs import expand_options, split_inputs
from robotdesc.commands.lint_replay import CheckedFile, ReplayRecord, argument
from robotdesc.commands.lint_report import (
    finish,
    known_inputs,
    split_outcomes,
    write_discovery,
)
from robotdesc.config import load_config
from robotdesc.errors import PINOCCHIO_HINT, InputError, UsageError
from robotdesc.expansion.launch import start_early
from robotdesc.kinematics.optional import pinocchio_available
from robotdesc.linting import result_cache
from robotdesc.linting.cached import cached_result
from robotdesc.linting.result import LintFailure, LintResult
from robotdesc.linting.targets import LintTarget, discover_targets, target_name
from robotdesc.output import RunInputs, check_output
from robotdesc.report.formats import FORMAT_NAMES, FORMATS
from robotdesc.rules.index import known_names
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
    """The handler: find the targets; when the whole-result cache answers every one, report
    its findings; else (fix,) lint, apply the baseline, report (`commands/lint_run.py`)."""
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
    searched = False
    for raw in paths:
        try:
            discovery = discover_targets(raw, explicit)
        except InputError as exc:
            failures.append(LintFailure(raw, exc))
            continue
        if discovery.directory:
            searched = True
            write_discovery(sys.stderr, discovery)
        failures.extend(LintFailure(link, InputError(
            "a symlink whose target lies outside the linted folder; not read", Span(link)))
            for link in discovery.refused)
        targets.extend(discovery.targets)
    targets = _with_cli_arguments(ns, targets, args)
    _check_lint_outputs(ns, targets)
    hits = _answers_from_cache(ns, targets, args, options, select, ignore)
    if hits is None:
        _start_worker_early(ns, targets)
        from robotdesc.commands.lint_run import lint_and_report  # the lint machinery

        return lint_and_report(ns, targets, failures, args, options, select, ignore)
    results, _ = split_outcomes(targets, hits, args)
    inputs = known_inputs(ns, targets, failures)
    for result in results:
        if result.inputs is not None:  # always, for a result read from the cache
            inputs += result.inputs
    if not (failures or searched or ns.output_file or ns.verbose):  # -v: this run's own log
        ns.replay = _replay_record(paths, inputs)
    return finish(ns, targets, results, failures, inputs)


def _start_worker_early(ns: argparse.Namespace, targets: list[LintTarget]) -> None:
    """Start the xacro worker before the lint machinery is imported, when this process lints
    a xacro target next (`expansion.launch.start_early`): a cold lint's worker then starts
    about 35 ms sooner. Not with --fix/--diff, a Dask cluster or worker processes."""
    if ns.fix or ns.diff or getattr(ns, "scheduler", None) or (ns.jobs != 1 and len(targets) > 1):
        return
    if not any(".xacro" in os.path.basename(target.path) for target in targets):
        return
    start_early()


def _replay_record(paths: Sequence[str], inputs: RunInputs) -> ReplayRecord | None:
    """What lets the next identical run replay this one (`commands/lint_replay.py`): every
    file the answer depended on, as the result cache verified it in this run; None when one
    was not verified here."""
    files = []
    for item in inputs.items:
        checked = result_cache.checked_digest(item.path)
        if checked is None:
            return None
        files.append(CheckedFile(item.path, *checked))
    return ReplayRecord(tuple(files), tuple(argument(path) for path in paths))


def _answers_from_cache(ns: argparse.Namespace, targets: list[LintTarget],
                        args: dict[str, str], options: ExpandOptions,
                        select: list[str] | None, ignore: list[str]) -> list[LintResult] | None:
    """Every target's stored result (`result_cache.load` checks each entry and re-hashes its
    inputs), or None when one is missing or the run fixes or uses a baseline."""
    if ns.fix or ns.diff or ns.baseline or ns.write_baseline:
        return None
    result_cache.new_run()
    hits = []
    for target in targets:
        hit = cached_result(target, args, options, select, ignore)
        if hit is None:
            return None
        hits.append(hit)
    return hits


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
    if found:  # checked against the rule index: no rule module is imported for it
        check_selectors(found, known_names(), flag)
    return found



def _check_lint_outputs(ns: argparse.Namespace, targets: list[LintTarget]) -> None:
    """Refuse, before any work, an output that is a target, the config or the baseline."""
    known = RunInputs().adding([ns.config, ns.baseline], "a file given to this run")
    known = known.adding([t.path for t in targets], "a description being checked")
    for path in (ns.output_file, ns.write_baseline):
        if path:
            check_output(path, known)
