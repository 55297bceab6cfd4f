"""`robotdesc rules` (the table of every rule) and `robotdesc rule CODE` (one rule's
documentation, options and defaults).

Exit codes: 0 printed, 2 an unknown rule. Both read the generated rule index
(`robotdesc.rules.index`), so that they start without importing every rule module; the
registry (and the error classes) only when the index does not know the rule.
"""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any

from robotdesc.commands.exit_codes import EXIT_OK
from robotdesc.report.table import render_table
from robotdesc.rules.index import read_index


def register(subparsers: Any, *, common: argparse.ArgumentParser,
             expansion: argparse.ArgumentParser) -> None:
    """Add the `rules` and `rule` subcommands (neither reads a description)."""
    rules = subparsers.add_parser("rules", parents=[common], help="list the rules",
                                  description="List every rule: code, name, family, severity, "
                                              "and whether it runs by default (opt-in rules "
                                              "run when --select names them, or ALL).")
    rules.add_argument("--format", choices=("text", "json"), default="text",
                       help="text: a table (the default); json: one object per rule")
    rules.set_defaults(handler=run_rules)

    rule = subparsers.add_parser("rule", parents=[common], help="show one rule's documentation",
                                 description="Show a rule's documentation, options and "
                                             "defaults.")
    rule.add_argument("code", metavar="CODE", help="a rule code (J101) or name")
    rule.set_defaults(handler=run_rule)


def run_rules(ns: argparse.Namespace) -> int:
    """The handler of `rules`: one row per rule (from the rule index when it is current)."""
    index = read_index()
    if index is not None:
        rows = list(index.rows)
    else:  # sources changed since the index was made: ask the registry (slower)
        from robotdesc.rules.docs import rule_rows

        rows = rule_rows()
    if getattr(ns, "format", "text") == "json":
        keys = ("code", "name", "family", "severity", "default", "summary")
        sys.stdout.write(json.dumps([dict(zip(keys, row)) for row in rows], indent=1) + "\n")
        return EXIT_OK
    header = ("CODE", "NAME", "FAMILY", "SEVERITY", "DEFAULT", "SUMMARY")
    sys.stdout.write(render_table(header, rows, max_cell=30))
    return EXIT_OK


def run_rule(ns: argparse.Namespace) -> int:
    """The handler of `rule CODE`.

    Raises:
        UsageError: no rule has this code or name.
    """
    index = read_index()
    text = None if index is None else index.find(ns.code)
    if text is None:  # unknown, or the index is out of date: ask the registry (slower)
        from robotdesc.errors import UsageError
        from robotdesc.rules.catalog import get_rule
        from robotdesc.rules.docs import rule_help

        found = get_rule(ns.code)
        if found is None:
            raise UsageError(f"unknown rule '{ns.code}' (see `robotdesc rules`)")
        text = rule_help(found)
    sys.stdout.write(text)
    return EXIT_OK
