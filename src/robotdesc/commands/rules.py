"""`robotdesc rules` (the table of every rule) and `robotdesc rule CODE` (one rule's
documentation, options and defaults).

Exit codes: 0 printed, 2 an unknown rule.
"""

from __future__ import annotations

import argparse
import json
import sys
from typing import TYPE_CHECKING, Any

from robotdesc.commands.inputs import EXIT_OK
from robotdesc.errors import UsageError
from robotdesc.report.table import render_table
from robotdesc.rules.fixes import FIXABLE

if TYPE_CHECKING:
    from robotdesc.rules.registry import Rule


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
    """The handler of `rules`: one row per rule."""
    from robotdesc.rules.catalog import all_rules

    rules = all_rules()
    if getattr(ns, "format", "text") == "json":
        payload = [{"code": r.code, "name": r.name, "family": r.family,
                    "severity": str(r.severity), "default": default_state(r),
                    "summary": r.summary} for r in rules]
        sys.stdout.write(json.dumps(payload, indent=1) + "\n")
        return EXIT_OK
    rows = [(r.code, r.name, r.family, str(r.severity), default_state(r), r.summary)
            for r in rules]
    header = ("CODE", "NAME", "FAMILY", "SEVERITY", "DEFAULT", "SUMMARY")
    sys.stdout.write(render_table(header, rows, max_cell=30))
    return EXIT_OK


def default_state(rule: Rule) -> str:
    """"on" for a rule that runs by default, "off" for an opt-in one."""
    return "off" if rule.opt_in else "on"


def run_rule(ns: argparse.Namespace) -> int:
    """The handler of `rule CODE`.

    Raises:
        UsageError: no rule has this code or name.
    """
    from robotdesc.rules.catalog import get_rule

    found = get_rule(ns.code)
    if found is None:
        raise UsageError(f"unknown rule '{ns.code}' (see `robotdesc rules`)")
    sys.stdout.write(rule_help(found))
    return EXIT_OK


def rule_help(rule: Rule) -> str:
    """A rule's documentation as `robotdesc rule CODE` prints it."""
    lines = [f"{rule.code} {rule.name}", "",
             f"Family: {rule.family}", f"Default severity: {rule.severity}",
             "Default: " + ("off (opt-in: select it by code, prefix, name or ALL)"
                            if rule.opt_in else "on")]
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
