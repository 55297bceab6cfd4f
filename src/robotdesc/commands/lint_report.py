"""The end of `robotdesc lint`: what a directory search found, the exit code, and the report
in the chosen format. Shared by a lint answered from the result cache (`commands/lint.py`)
and one that checks (`commands/lint_run.py`); imports none of the lint machinery."""

from __future__ import annotations

import argparse
import dataclasses
import logging
import os
import sys
from collections.abc import Mapping, Sequence
from typing import TextIO

from robotdesc.commands.inputs import EXIT_FINDINGS, EXIT_INPUT, EXIT_OK
from robotdesc.diagnostics import Severity
from robotdesc.linting.result import LintFailure, LintResult
from robotdesc.linting.targets import Discovery, LintTarget, target_name
from robotdesc.output import RunInputs, write_output
from robotdesc.report.formats import render_report
from robotdesc.report.statistics import render_statistics_json, render_statistics_text
from robotdesc.report.text import render_failure, render_text, write_text

log = logging.getLogger(__name__)

Outcome = LintResult | LintFailure


def split_outcomes(targets: Sequence[LintTarget], outcomes: Sequence[Outcome],
                   args: Mapping[str, str]) -> tuple[list[LintResult], list[LintFailure]]:
    """The results (each with the arguments it was linted with) and the failures."""
    results = [dataclasses.replace(o, args=tuple({**dict(t.args), **args}.items()))
               for t, o in zip(targets, outcomes) if isinstance(o, LintResult)]
    return results, [o for o in outcomes if isinstance(o, LintFailure)]


def known_inputs(ns: argparse.Namespace, targets: Sequence[LintTarget],
                 failures: Sequence[LintFailure]) -> RunInputs:
    """The files given to the run and the targets (no output may replace one)."""
    inputs = RunInputs().adding([ns.config, ns.baseline], "a file given to this run")
    return inputs.adding([t.path for t in targets] + [f.target for f in failures],
                         "a description being checked")


def finish(ns: argparse.Namespace, targets: Sequence[LintTarget], results: list[LintResult],
           failures: list[LintFailure], inputs: RunInputs) -> int:
    """Print the failures and the report; the exit code."""
    fail_on = {t.path: Severity.parse(ns.fail_on) if ns.fail_on else t.config.fail_on
               for t in targets}
    failed = any(r.failed(fail_on.get(r.target, Severity.INFO)) for r in results)
    if ns.format == "text":
        for failure in failures:  # path:line:col: error: message, the source, the call chain
            sys.stderr.write(render_failure(LintFailure(failure.target or "robotdesc",
                                                        failure.error)))
    _write_report(ns, results, failures, min(fail_on.values(), default=Severity.INFO), inputs)
    return EXIT_INPUT if failures else EXIT_FINDINGS if failed else EXIT_OK


def write_discovery(stream: TextIO, discovery: Discovery) -> None:
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


def _write_report(ns: argparse.Namespace, results: list[LintResult],
                  failures: list[LintFailure], fail_on: Severity, inputs: RunInputs) -> None:
    """Render the report in the chosen format to --output-file or stdout."""
    colour = not ns.output_file and use_colour(sys.stdout)
    text = _render_report(ns.format, ns.statistics, results, failures, fail_on, colour)
    if text is None:  # coloured text straight to the terminal
        write_text(sys.stdout, results, failures, colour=use_colour(sys.stdout))
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


def use_colour(stream: TextIO) -> bool:
    """Colour on a terminal, unless NO_COLOR is set; FORCE_COLOR forces it."""
    if os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    return bool(getattr(stream, "isatty", lambda: False)())
