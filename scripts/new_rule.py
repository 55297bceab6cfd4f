"""Scaffold a new lint rule: its code with the three-part docs, a fixture, a test.

    python scripts/new_rule.py J111 joint-without-name --family joints --severity warning

appends the rule to its family's module in src/robotdesc/rules/ (the module whose `FAMILY`
is the family: the one named after it when several are, or the one --module names; a new
module `<family>.py` when the family has none yet), writes
tests/rules/fixtures/<family>/<name>.urdf (one finding marked, one clean line) and
tests/rules/test_<name with underscores>.py, then tells you what is left by hand: the import
in rules/catalog.py (for a new module) and `python -m robotdesc.rules.docs > docs/rules.md`.
With --fix safe|unsafe the rule is entered in rules/fixes.py's FIXABLE and the script names
what the finding must carry (its `changes`). See docs/contributing.md.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

RULE = '''

@rule("{code}", "{name}", family=FAMILY, severity=Severity.{severity})
def {function}(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds ... (one sentence: what the rule reports).

    More detail: when it fires and when it stays silent.

    Why is this bad?
    What goes wrong in ROS, Gazebo, MoveIt or a simulator, in a user's words.

    Example
    ```xml
    <robot name="r">
      <link name="base"/>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="r">
      <link name="base"/>
    </robot>
    ```
    """
    for link in robot.links:
        if False:  # the condition
            yield Finding(f"link '{{link.name}}': ...", link.where, f"link:{{link.name}}")
'''

MODULE_HEAD = '''"""{family} rules ({prefix}): ..."""

from __future__ import annotations

from collections.abc import Iterator

from robotdesc.diagnostics import Finding, Severity
from robotdesc.model.elements import Robot
from robotdesc.rules.registry import RuleContext, rule

FAMILY = "{family}"
'''

FIXTURE = '''<?xml version="1.0"?>
<!-- {code} {name}: the marked line must give the finding, every other line none. -->
<robot name="{function}">
  <link name="base"/>  <!-- expect: {code} -->
</robot>
'''

TEST = '''"""{code} {name}: found where the fixture marks it (tests/rules/test_fixtures.py runs every
fixture); here, the real-world cases that must stay silent."""

from __future__ import annotations

from robotdesc.model.parse import parse_urdf
from robotdesc.rules.catalog import get_rule
from robotdesc.rules.registry import RuleContext, run_rule

SILENT = b"""<robot name="r"><link name="base"/></robot>"""


def test_{function}_stays_silent_on_a_clean_robot() -> None:
    rule = get_rule("{code}")
    assert rule is not None
    robot = parse_urdf(SILENT, "silent.urdf")
    assert list(run_rule(rule, robot, RuleContext(options=rule.default_options()))) == []
'''


def family_module(rules_dir: Path, family: str, chosen: str | None) -> Path | str:
    """The module the rule goes in, or why none can be chosen."""
    if chosen:
        path = rules_dir / f"{chosen}.py"
        return path if path.is_file() else f"{path} does not exist"
    declared = re.compile(rf'^FAMILY = "{re.escape(family)}"$', re.M)
    found = sorted(p for p in rules_dir.glob("*.py") if declared.search(p.read_text()))
    named = [p for p in found if p.stem == family]
    if named or len(found) == 1:
        return (named or found)[0]
    if found:
        return (f"the family {family} has several modules ({', '.join(p.stem for p in found)}): "
                "pass --module")
    return rules_dir / f"{family}.py"


def add_fixable(fixes: Path, code: str, applicability: str) -> None:
    """Enter the rule in FIXABLE (rules/fixes.py), keeping the codes in order."""
    if not fixes.is_file():
        return
    text = fixes.read_text()
    entry = f'    "{code}": Applicability.{applicability.upper()},\n'
    opening = re.search(r"^FIXABLE\b.*\{\n", text, re.M)
    if opening is None:
        return
    start, end = opening.start(), text.index("\n}", opening.end()) + 1
    lines = text[start:end].splitlines(keepends=True)
    body = [line for line in lines[1:] if line.strip()] + [entry]
    body.sort(key=lambda line: line.strip())
    fixes.write_text(text[:start] + lines[0] + "".join(body) + text[end:])


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("code", help="the rule's code, e.g. J111 (its prefix names the family)")
    parser.add_argument("name", help="kebab-case name, e.g. joint-without-name")
    parser.add_argument("--family", required=True, help="a family of rules.registry.FAMILIES")
    parser.add_argument("--severity", choices=("error", "warning", "info"), default="warning")
    parser.add_argument("--module", help="the rule module to append to (default: the "
                                         "family's module)")
    parser.add_argument("--fix", choices=("safe", "unsafe"),
                        help="the rule's findings carry a fix of this applicability")
    parser.add_argument("--root", type=Path, default=ROOT, help="the repository (for tests)")
    ns = parser.parse_args(argv)
    if not re.fullmatch(r"[A-Z]{1,3}\d{3}", ns.code) or \
            not re.fullmatch(r"[a-z0-9]+(-[a-z0-9]+)*", ns.name):
        parser.error("the code looks like J111 and the name like joint-without-name")
    function = ns.name.replace("-", "_")
    values = {"code": ns.code, "name": ns.name, "function": function, "family": ns.family,
              "severity": ns.severity.upper(), "prefix": ns.code.rstrip("0123456789")}
    rules_dir = ns.root / "src" / "robotdesc" / "rules"
    module = family_module(rules_dir, ns.family, ns.module)
    if isinstance(module, str):
        parser.error(module)
    created = not module.is_file()
    if created:
        module.write_text(MODULE_HEAD.format(**values) + RULE.format(**values))
    else:
        text = module.read_text()
        if f'@rule("{ns.code}"' in text:
            parser.error(f"{module} already has {ns.code}")
        module.write_text(text.rstrip("\n") + "\n" + RULE.format(**values))
    if ns.fix:
        add_fixable(rules_dir / "fixes.py", ns.code, ns.fix)
    fixture = ns.root / "tests" / "rules" / "fixtures" / ns.family / f"{function}.urdf"
    fixture.parent.mkdir(parents=True, exist_ok=True)
    fixture.write_text(FIXTURE.format(**values))
    test = ns.root / "tests" / "rules" / f"test_{function}.py"
    test.write_text(TEST.format(**values))
    print(f"wrote {module}\nwrote {fixture}\nwrote {test}")
    if created:
        print(f"now add `{module.stem},` to the import list in src/robotdesc/rules/catalog.py")
    if ns.fix:
        print(f"{ns.code} is {ns.fix} in rules/fixes.py: give each Finding its fix text and its "
              "changes (diagnostics.ValueChange: element, attribute, new value); the edit "
              "engine writes them (or unfixable=\"why not\" when a finding cannot be fixed)")
    print("then write the check, and: python -m robotdesc.rules.docs > docs/rules.md && "
          "python -m robotdesc.rules.docs --index")
    return 0


if __name__ == "__main__":
    sys.exit(main())
