"""The --fix, --diff and --unsafe-fixes options of `robotdesc lint` (not a subcommand of its
own: commands/lint.py calls `run_fixes` before it reports)."""

from __future__ import annotations

import argparse
import logging
import os
import sys
from typing import Mapping, Sequence

from robotdesc.diagnostics import Diagnostic
from robotdesc.expansion import ExpandOptions
from robotdesc.linting.fix.engine import NOT_APPLICABLE, UNSAFE
from robotdesc.linting.fix.run import fix_targets
from robotdesc.linting.merge import finding_key
from robotdesc.linting.targets import LintTarget

log = logging.getLogger(__name__)


def run_fixes(ns: argparse.Namespace, targets: Sequence[LintTarget], args: Mapping[str, str],
              options: ExpandOptions, select: Sequence[str] | None,
              ignore: Sequence[str]) -> int:
    """Fix (or diff) the targets' findings; returns --diff's exit code (1: a diff)."""
    run = fix_targets(targets, args=args, expand_options=options, select=select,
                      ignore=ignore, unsafe=ns.unsafe_fixes, write=not ns.diff)
    err = sys.stderr
    said: set[str] = set()  # one line per problem, not per element and variant
    for outcome in run.outcomes:
        line = (f"robotdesc: {_where(outcome.diagnostic)}: {outcome.diagnostic.code} "
                f"fix not applicable: {outcome.reason}\n")
        if outcome.status == NOT_APPLICABLE and line not in said:
            said.add(line)
            err.write(line)
    hidden = len({finding_key(o.diagnostic, o.diagnostic.target) for o in run.outcomes
                  if o.status == UNSAFE})
    if ns.diff:
        sys.stdout.write(run.diff)
        count = len({frozenset((e.path, e.start, e.end) for e in o.edits)
                     for o in run.outcomes if o.status == "fixed"})
        err.write(f"robotdesc: {count} fix(es) would be applied"
                  + (f"; {hidden} more with --unsafe-fixes" if hidden else "") + "\n")
        return 1 if run.diff else 0
    for path in run.refused:
        err.write(f"robotdesc: not writing {path}: it changed since it was read; run again\n")
    err.write(f"robotdesc: fixed {run.fixed} finding(s) in {len(run.written)} file(s)"
              + (f"; {hidden} more fixable with --unsafe-fixes" if hidden else "") + "\n")
    return 0


def _where(diagnostic: Diagnostic) -> str:
    span = diagnostic.where.span if diagnostic.where else None
    if span is None:
        return diagnostic.target
    path = os.path.relpath(span.path) if os.path.isabs(span.path) else span.path
    return f"{path}:{span.line}" if span.line else path
