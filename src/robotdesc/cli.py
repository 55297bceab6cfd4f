"""The `robotdesc` command: parse arguments, call the API, render, choose the exit code.

Exit codes: 0 no finding at or above --fail-on, 1 findings, 2 an input could not be checked
(or the command line is wrong), 3 internal error (a bug), 130 interrupted.
Heavy modules are imported inside the commands so that `robotdesc --help` starts fast.
"""

from __future__ import annotations

import argparse
import dataclasses
import importlib
import logging
import os
import sys
from typing import Any, Sequence

from robotdesc._version import __version__
from robotdesc.commands import COMMAND_MODULES
from robotdesc.commands.inputs import (
    EXIT_FINDINGS,
    EXIT_INPUT,
    EXIT_INTERNAL,
    EXIT_INTERRUPTED,
    EXIT_OK,
    expand_options,
    single_input,
    split_inputs,
)
from robotdesc.config import load_config
from robotdesc.diagnostics import Severity
from robotdesc.errors import InputError, UsageError
from robotdesc.expansion import expand_file
from robotdesc.linting.baseline import apply_baseline, read_baseline, render_baseline
from robotdesc.linting.inputs import description_inputs, expansion_inputs, run_inputs
from robotdesc.linting.result import LintFailure, LintResult
from robotdesc.linting.select import unknown_selectors
from robotdesc.linting.targets import discover_targets, target_name
from robotdesc.output import NO_INPUTS, RunInputs, check_output
from robotdesc.output import write_output as write
from robotdesc.progress import progress_for
from robotdesc.report.formats import FORMAT_NAMES, FORMATS, render_report
from robotdesc.report.statistics import render_statistics_json, render_statistics_text
from robotdesc.report.table import render_table
from robotdesc.report.text import render_failure, render_text, write_text
from robotdesc.rules.fixes import FIXABLE

BUG_REPORT_URL = "https://github.com/robotdesc/robotdesc/issues"

log = logging.getLogger("robotdesc.cli")


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code (the console script exits with it)."""
    parser = build_parser()
    try:
        ns = parser.parse_args(argv)
    except SystemExit as exc:  # --help, --version (0) and usage errors (2)
        return exc.code if isinstance(exc.code, int) else EXIT_INPUT
    verbose = getattr(ns, "verbose", 0)
    restore = _configure_logging(verbose)
    try:
        return _run(ns, verbose)
    finally:
        restore()  # leave the "robotdesc" logger as it was (main() may run in-process)


def _run(ns: argparse.Namespace, verbose: int) -> int:
    """Run the chosen command, turning every failure into its exit code."""
    try:
        return ns.handler(ns)
    except KeyboardInterrupt:
        sys.stderr.write("robotdesc: interrupted\n")
        return EXIT_INTERRUPTED
    except InputError as exc:
        _write_input_error(sys.stderr, exc, None)
        return EXIT_INPUT
    except BrokenPipeError:  # e.g. `robotdesc rules | head`
        _silence_stdout()
        return EXIT_OK
    except Exception as exc:  # anything else is a bug: say so, keep the traceback for -v
        detail = str(exc)
        detail = detail if len(detail) <= 500 else detail[:500] + f"... ({len(detail)} characters)"
        sys.stderr.write(f"robotdesc: internal error: {type(exc).__name__}: {detail}\n"
                         f"This is a bug in robotdesc, not a problem with your files; please "
                         f"report it at {BUG_REPORT_URL} "
                         "with the command you ran"
                         + (".\n" if verbose else " (run with --verbose for the traceback).\n"))
        if verbose:
            import traceback

            traceback.print_exc(file=sys.stderr)
        return EXIT_INTERNAL


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of every subcommand (cheap: no heavy imports)."""
    parser = argparse.ArgumentParser(
        prog="robotdesc",
        description="Expand xacro without ROS, and lint robot descriptions (URDF/xacro).",
        epilog="Exit codes: 0 clean, 1 findings, 2 input could not be checked, 3 internal error.")
    parser.add_argument("--version", action="version", version=f"robotdesc {_version()}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)

    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("-v", "--verbose", action="count", default=0,
                        help="log package resolution and progress to stderr (twice: debug)")
    common.add_argument("-q", "--quiet", action="store_true",
                        help="no progress on stderr (shown for long runs: a bar on a "
                             "terminal, a line every few seconds otherwise)")
    expansion = argparse.ArgumentParser(add_help=False)
    expansion.add_argument("--package-path", action="append", default=[], metavar="DIR",
                           help="a folder holding ROS packages (or one package); repeatable; "
                                "searched first")
    expansion.add_argument("--trusted", action="store_true",
                           help="lift the sandbox limits (only for your own files)")
    expansion.add_argument("--no-cache", action="store_true",
                           help="expand again even when no input changed")
    expansion.add_argument("--config", metavar="FILE",
                           help="use this robotdesc.toml / pyproject.toml instead of searching")
    expansion.add_argument("--timeout", type=float, default=60.0, metavar="SECONDS",
                           help="wall-clock limit of one xacro expansion (default: 60)")
    expansion.add_argument("--env", action="append", default=[], metavar="NAME",
                           help="let $(env NAME)/$(optenv NAME) see this variable in safe mode; "
                                "repeatable")

    lint = commands.add_parser(
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
    lint.add_argument("--jobs", "-j", type=int, default=1, metavar="N",
                      help="lint N targets at once in worker processes (0: one per CPU; "
                           "default: 1)")
    lint.add_argument("--fix", action="store_true",
                      help="write the safe fixes of findings into the xacro/URDF sources "
                           "(where the value is a literal), then report what remains")
    lint.add_argument("--diff", action="store_true",
                      help="print the fixes as a unified diff and write nothing")
    lint.add_argument("--unsafe-fixes", action="store_true",
                      help="with --fix or --diff, apply the unsafe fixes too (inertia, "
                           "limits, mesh scale)")
    lint.set_defaults(handler=_run_lint)

    expand = commands.add_parser(
        "expand", parents=[common, expansion], help="expand a xacro file to URDF",
        description="Expand a xacro file to URDF without ROS (written to stdout or -o).")
    expand.add_argument("inputs", nargs="+", metavar="FILE | name:=value",
                        help="the xacro file, then xacro arguments")
    expand.add_argument("-o", "--output", metavar="OUT", help="write the URDF to OUT")
    expand.set_defaults(handler=_run_expand)

    rules = commands.add_parser("rules", parents=[common], help="list the rules",
                                description="List every rule: code, name, family, severity.")
    rules.set_defaults(handler=_run_rules)

    rule = commands.add_parser("rule", parents=[common], help="show one rule's documentation",
                               description="Show a rule's documentation, options and defaults.")
    rule.add_argument("code", metavar="CODE", help="a rule code (J101) or name")
    rule.set_defaults(handler=_run_rule)

    for module in COMMAND_MODULES:  # each: register(commands, common=..., expansion=...)
        importlib.import_module(module).register(commands, common=common, expansion=expansion)
    return parser


# --- commands -----------------------------------------------------------------------------


def _run_lint(ns: argparse.Namespace) -> int:
    if ns.statistics and ns.format not in ("text", "json"):
        raise UsageError("--statistics works with --format text or json")
    if ns.jobs < 0:
        raise UsageError("--jobs must be 0 (one per CPU) or positive")
    paths, args = split_inputs(ns.inputs)
    select = _selectors(ns.select, "--select") or None
    ignore = _selectors(ns.ignore, "--ignore")
    options = expand_options(ns)
    explicit = load_config(ns.config) if ns.config else None

    targets, failures = [], []
    for raw in paths:
        try:
            discovery = discover_targets(raw, explicit)
        except InputError as exc:
            failures.append(LintFailure(raw, exc))
            continue
        if discovery.directory:
            _write_discovery(sys.stderr, discovery)
        targets.extend(discovery.targets)
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
        for failure in failures:
            _write_input_error(sys.stderr, failure.error, failure.target)
    _write_report(ns, results, failures, min(fail_on.values(), default=Severity.INFO), inputs)
    return EXIT_INPUT if failures else EXIT_FINDINGS if failed else EXIT_OK


def _lint_with_progress(ns: argparse.Namespace, targets: list, args: dict, options: Any,
                        select: Any, ignore: list) -> list:
    """`lint_targets` with progress on stderr: target by target in this process, or as one
    step with worker processes."""
    from robotdesc.linting.parallel import effective_jobs, lint_targets

    with progress_for(ns, "lint", total=len(targets), unit="targets") as progress:
        if min(effective_jobs(ns.jobs), len(targets)) > 1:
            progress.update(0, detail=f"{effective_jobs(ns.jobs)} worker processes")
            return lint_targets(targets, args=args, expand_options=options, select=select,
                                ignore=ignore, jobs=ns.jobs)
        outcomes = []
        for number, target in enumerate(targets):
            progress.update(number, detail=target.name())
            outcomes += lint_targets([target], args=args, expand_options=options,
                                     select=select, ignore=ignore, jobs=1)
        return outcomes


def _check_lint_outputs(ns: argparse.Namespace, targets: list) -> None:
    """Refuse, before any work, an output that is a target, the config or the baseline."""
    known = RunInputs().adding([ns.config, ns.baseline], "a file given to this run")
    known = known.adding([t.path for t in targets], "a description being checked")
    for path in (ns.output_file, ns.write_baseline):
        if path:
            check_output(path, known)


def _lint_inputs(ns: argparse.Namespace, targets: list, results: list, failures: list,
                 options: Any) -> Any:
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


def _write_discovery(stream: Any, discovery: Any) -> None:
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
    if discovery.unlisted:
        text += (f"; skipped {len(discovery.unlisted)} file(s) not in their config's targets: "
                 + listing([target_name(p, (), base) for p in discovery.unlisted]))
    stream.write(text + "\n")


def _apply_baseline(ns: argparse.Namespace, results: list, inputs: Any) -> list:
    """--write-baseline records the findings; --baseline (or the written one) hides them."""
    if ns.write_baseline:
        write_output(ns.write_baseline, render_baseline(results, ns.write_baseline)
                     .encode("utf-8"), inputs)
        count = sum(len(r.diagnostics) for r in results)
        sys.stderr.write(f"robotdesc: wrote {count} finding(s) to {ns.write_baseline}\n")
    path = ns.write_baseline or ns.baseline
    if not path:
        return results
    outcome = apply_baseline(results, read_baseline(path),
                             os.path.dirname(os.path.abspath(path)))
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


def _run_expand(ns: argparse.Namespace) -> int:
    from robotdesc.model.write import urdf_text

    single = single_input(ns, "expand")
    source = single.source
    known = description_inputs(source, single.config.path)
    if ns.output:
        check_output(ns.output, known)
    # as the xacro command: a file that holds substitutions is expanded whatever its name
    options = dataclasses.replace(single.options, substitutions_in_urdf=True)
    expanded = expand_file(source, single.args, options=options)
    urdf = urdf_text(expanded.xml, expanded.source)
    if not ns.output:
        sys.stdout.buffer.write(urdf)
        sys.stdout.flush()
        return EXIT_OK
    write_output(ns.output, urdf, known + expansion_inputs(expanded))
    log.info("wrote %s (%d bytes)", ns.output, len(urdf))
    return EXIT_OK


def _run_rules(ns: argparse.Namespace) -> int:
    from robotdesc.rules.catalog import all_rules

    rows = [(r.code, r.name, r.family, str(r.severity), r.summary) for r in all_rules()]
    header = ("CODE", "NAME", "FAMILY", "SEVERITY", "SUMMARY")
    sys.stdout.write(render_table(header, rows, max_cell=30))
    return EXIT_OK


def _run_rule(ns: argparse.Namespace) -> int:
    from robotdesc.rules.catalog import get_rule

    found = get_rule(ns.code)
    if found is None:
        raise UsageError(f"unknown rule '{ns.code}' (see `robotdesc rules`)")
    sys.stdout.write(rule_help(found))
    return EXIT_OK


def rule_help(rule: Any) -> str:
    """A rule's documentation as `robotdesc rule CODE` prints it."""
    lines = [f"{rule.code} {rule.name}", "",
             f"Family: {rule.family}", f"Default severity: {rule.severity}"]
    if rule.needs:
        lines.append(f"Needs: {', '.join(sorted(rule.needs))}")

    if rule.code in FIXABLE:
        applicability = FIXABLE[rule.code].value
        lines.append(f"Fix: {applicability} (applied by `robotdesc lint --fix`"
                     + (" --unsafe-fixes)" if applicability == "unsafe" else ")"))
    lines += ["", rule.doc or rule.summary, ""]
    fields = rule.option_fields()
    if fields:
        defaults = rule.default_options()
        lines.append(f"Options ([tool.robotdesc.rules.{rule.code}]):")
        for field in fields:
            kind = field.type if isinstance(field.type, str) else getattr(
                field.type, "__name__", str(field.type))
            lines.append(f"  {field.name} ({kind}) = {getattr(defaults, field.name)!r}")
        lines.append("")
    else:
        lines += ["Options: none", ""]
    return "\n".join(lines)


# --- helpers ------------------------------------------------------------------------------


def _selectors(values: Sequence[str], flag: str) -> list[str]:
    """Comma-separated selectors from repeatable flags, checked against the registry."""
    from robotdesc.rules.catalog import all_rules

    selectors = [part.strip() for value in values for part in value.split(",") if part.strip()]
    if selectors:
        unknown = unknown_selectors(selectors, all_rules())
        if unknown:
            raise UsageError(f"{flag}: no rule matches '{unknown[0]}' (see `robotdesc rules`)")
    return selectors


def _write_report(ns: argparse.Namespace, results: list, failures: list,
                  fail_on: Any, inputs: Any = None) -> None:
    """Render the report in the chosen format to --output-file or stdout."""
    colour = not ns.output_file and _use_colour(sys.stdout)
    text = _render_report(ns.format, ns.statistics, results, failures, fail_on, colour)
    if text is None:  # coloured text straight to the terminal

        write_text(sys.stdout, results, failures, colour=_use_colour(sys.stdout))
    elif ns.output_file:
        write_output(ns.output_file, text.encode("utf-8"), inputs)
    else:
        sys.stdout.write(text)


def _render_report(fmt: str, statistics: bool, results: list, failures: list,
                   fail_on: Any, colour: bool) -> str | None:
    """The report text (None: text format for a terminal, written by `write_text`)."""
    if statistics:
        return (render_statistics_json if fmt == "json" else render_statistics_text)(results)
    if fmt != "text":
        return render_report(fmt, results, failures, fail_on)
    return None if colour else render_text(results, failures)


def _write_input_error(stream: Any, error: Any, target: str | None) -> None:
    """`path:line:col: error: message`, the source line and the macro call chain."""
    stream.write(render_failure(LintFailure(target or "robotdesc", error)))


def write_output(path: str, data: bytes, inputs: Any = None) -> None:
    """Write a command's output through `robotdesc.output.write_output` (which refuses to
    replace any of `inputs`, the files the run read)."""
    write(path, data, inputs if inputs is not None else NO_INPUTS)


def same_file(a: str, b: str) -> bool:
    return os.path.realpath(a) == os.path.realpath(b)


def _use_colour(stream: Any) -> bool:
    if os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    return bool(getattr(stream, "isatty", lambda: False)())


def _configure_logging(verbose: int):
    """Log robotdesc's messages to stderr; returns a function that undoes it."""
    level = logging.WARNING if not verbose else logging.INFO if verbose == 1 else logging.DEBUG
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("robotdesc: %(message)s"))
    root = logging.getLogger("robotdesc")
    saved = (root.handlers[:], root.level, root.propagate)
    root.handlers[:] = [handler]
    root.setLevel(level)
    root.propagate = False

    def restore() -> None:
        root.handlers[:], root.level, root.propagate = saved[0], saved[1], saved[2]

    return restore


def _silence_stdout() -> None:
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())


def _version() -> str:

    return __version__

