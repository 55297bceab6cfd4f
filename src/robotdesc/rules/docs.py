"""Render the rule reference (docs/rules.md) from the registry.

Regenerate with `python -m robotdesc.rules.docs > docs/rules.md`; a test keeps it current.
The same module writes the rule index that `robotdesc rules` and `robotdesc rule` read
(`python -m robotdesc.rules.docs --index`, see `robotdesc.rules.index`).
"""

from __future__ import annotations

import dataclasses
import inspect
import sys

from robotdesc.rules.catalog import all_rules
from robotdesc.rules.fixes import FIXABLE
from robotdesc.rules.index import INDEX_FILE, Row, index_document
from robotdesc.rules.registry import Rule

#: Lines of a rule docstring that become section headings.
SECTION_HEADINGS = ("Why is this bad?", "Example")

REGENERATE = "python -m robotdesc.rules.docs > docs/rules.md"
REGENERATE_INDEX = "python -m robotdesc.rules.docs --index"


def render_rules_markdown() -> str:
    """The whole rule reference as Markdown: an index table, then one section per rule."""
    rules = all_rules()
    parts = [
        "# Rules\n",
        f"<!-- Generated from the rule registry by `{REGENERATE}`. Do not edit by hand. -->\n",
        ("Each rule has a stable code and a kebab-case name that names the problem. A finding "
        "can be suppressed on its element with `<!-- robotdesc: ignore CODE -->` "
        "(see RD001).\n"),
        ("Default on: the rule runs without `--select`. Default off (opt-in): it runs when "
         "`--select` or the config's `select` names it (its code, a prefix, its name, or "
         "`ALL`); docs/precision.md says why each rule is where it is.\n"),
        "| Code | Name | Family | Default severity | Default |",
        "|------|------|--------|------------------|---------|",
    ]
    parts += [f"| [{r.code}](#{rule_anchor(r)}) | {r.name} | {r.family} | {r.severity} | "
              f"{'off' if r.opt_in else 'on'} |" for r in rules]
    parts.append("")
    for rule_ in rules:
        parts.append(_render_rule(rule_))
    return "\n".join(parts).rstrip("\n") + "\n"


def rule_anchor(rule_: Rule) -> str:
    return f"{rule_.code}-{rule_.name}".lower()


def _render_rule(rule_: Rule) -> str:
    facts = [f"Family: {rule_.family}", f"Default severity: {rule_.severity}",
             "Default: " + ("off (opt-in)" if rule_.opt_in else "on")]
    if rule_.needs:
        facts.append("Needs: " + ", ".join(sorted(rule_.needs)))
    if rule_.code in FIXABLE:
        unsafe = " --unsafe-fixes" if FIXABLE[rule_.code].value == "unsafe" else ""
        facts.append(f"Fix: {FIXABLE[rule_.code]} (`robotdesc lint --fix{unsafe}`)")
    lines = [f"## {rule_.code} {rule_.name}", "", " · ".join(facts), ""]
    for line in rule_.doc.splitlines():
        if line.strip() in SECTION_HEADINGS:
            lines += [f"### {line.strip()}", ""]
        else:
            lines.append(line)
    lines.append("")
    options = _render_options(rule_)
    if options:
        lines += ["### Options", "", *options, ""]
    return "\n".join(lines)


def _render_options(rule_: Rule) -> list[str]:
    fields = rule_.option_fields()
    if not fields or rule_.options is None:
        return []
    described = _attribute_descriptions(rule_.options)
    rows = ["| Option | Type | Default | Description |",
            "|--------|------|---------|-------------|"]
    for field in fields:
        default = field.default if field.default is not dataclasses.MISSING else "(required)"
        rows.append(f"| `{field.name}` | {_type_name(field.type)} | `{default!r}` | "
                    f"{described.get(field.name, '')} |")
    return rows


def _type_name(annotation: object) -> str:
    """An option's type as written (annotations are strings in the rule modules)."""
    if isinstance(annotation, str):
        return annotation
    return annotation.__name__ if isinstance(annotation, type) else ""


def _attribute_descriptions(options: type) -> dict[str, str]:
    """Parse the `Attributes:` section of an options dataclass's Google-style docstring."""
    doc = inspect.cleandoc(options.__doc__ or "")
    described: dict[str, str] = {}
    current = None
    inside = False
    for line in doc.splitlines():
        if line.strip() == "Attributes:":
            inside = True
            continue
        if not inside or not line.strip():
            continue
        if not line.startswith(" "):
            break
        name, colon, text = line.strip().partition(":")
        if colon and line.startswith("    ") and not line.startswith("     ") and " " not in name:
            current = name
            described[name] = text.strip()
        elif current:
            described[current] += " " + line.strip()
    return described


def rule_help(rule_: Rule) -> str:
    """A rule's documentation as `robotdesc rule CODE` prints it."""
    lines = [f"{rule_.code} {rule_.name}", "",
             f"Family: {rule_.family}", f"Default severity: {rule_.severity}",
             "Default: " + ("off (opt-in: select it by code, prefix, name or ALL)"
                            if rule_.opt_in else "on")]
    if rule_.needs:
        lines.append(f"Needs: {', '.join(sorted(rule_.needs))}")

    if rule_.code in FIXABLE:
        applicability = FIXABLE[rule_.code].value
        lines.append(f"Fix: {applicability} (applied by `robotdesc lint --fix`"
                     + (" --unsafe-fixes)" if applicability == "unsafe" else ")"))
    lines += ["", rule_.doc or rule_.summary, ""]
    fields = rule_.option_fields()
    if fields:
        defaults = rule_.default_options()
        lines.append(f"Options ([tool.robotdesc.rules.{rule_.code}]):")
        for field in fields:
            kind = field.type if isinstance(field.type, str) else getattr(
                field.type, "__name__", str(field.type))
            lines.append(f"  {field.name} ({kind}) = {getattr(defaults, field.name)!r}")
        lines.append("")
    else:
        lines += ["Options: none", ""]
    return "\n".join(lines)


def default_state(rule_: Rule) -> str:
    """"on" for a rule that runs by default, "off" for an opt-in one."""
    return "off" if rule_.opt_in else "on"


def rule_rows() -> list[Row]:
    """(code, name, family, severity, default, summary) per rule, as `robotdesc rules`
    lists them."""
    return [(r.code, r.name, r.family, str(r.severity), default_state(r), r.summary)
            for r in all_rules()]


def render_index() -> str:
    """The rule index (`robotdesc.rules.index`) made from the registry."""
    return index_document(rule_rows(), {r.code: rule_help(r) for r in all_rules()})


def main(argv: list[str] | None = None) -> None:
    """Write the rule reference to stdout; with `--index`, rewrite the rule index."""
    if "--index" in (sys.argv[1:] if argv is None else argv):
        with open(INDEX_FILE, "w", encoding="utf-8") as stream:
            stream.write(render_index())
        return
    sys.stdout.write(render_rules_markdown())


if __name__ == "__main__":
    main()
