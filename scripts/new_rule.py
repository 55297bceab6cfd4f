"""Scaffold a new lint rule: its code with the three-part docs, a fixture, a test.

    python scripts/new_rule.py J111 joint-without-name --family joints --severity warning

writes src/robotdesc/rules/<module>.py (a new module, or appends to the family's module with
--module), tests/rules/fixtures/<family>/<name>.urdf (one finding marked, one clean line) and
tests/rules/test_<name with underscores>.py, then tells you the two lines to edit by hand:
the import in rules/catalog.py (for a new module) and `python -m robotdesc.rules.docs >
docs/rules.md`. See docs/contributing.md.
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


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("code", help="the rule's code, e.g. J111 (its prefix names the family)")
    parser.add_argument("name", help="kebab-case name, e.g. joint-without-name")
    parser.add_argument("--family", required=True, help="a family of rules.registry.FAMILIES")
    parser.add_argument("--severity", choices=("error", "warning", "info"), default="warning")
    parser.add_argument("--module", help="an existing rule module to append to (default: new)")
    parser.add_argument("--root", type=Path, default=ROOT, help="the repository (for tests)")
    ns = parser.parse_args(argv)
    if not re.fullmatch(r"[A-Z]{1,3}\d{3}", ns.code) or \
            not re.fullmatch(r"[a-z0-9]+(-[a-z0-9]+)*", ns.name):
        parser.error("the code looks like J111 and the name like joint-without-name")
    function = ns.name.replace("-", "_")
    values = {"code": ns.code, "name": ns.name, "function": function, "family": ns.family,
              "severity": ns.severity.upper(), "prefix": ns.code.rstrip("0123456789")}
    rules_dir = ns.root / "src" / "robotdesc" / "rules"
    module = rules_dir / f"{ns.module or function}.py"
    if ns.module:
        if not module.is_file():
            parser.error(f"{module} does not exist")
        module.write_text(module.read_text().rstrip("\n") + "\n" + RULE.format(**values))
    else:
        if module.exists():
            parser.error(f"{module} exists: pass --module {module.stem}")
        module.write_text(MODULE_HEAD.format(**values) + RULE.format(**values))
    fixture = ns.root / "tests" / "rules" / "fixtures" / ns.family / f"{function}.urdf"
    fixture.parent.mkdir(parents=True, exist_ok=True)
    fixture.write_text(FIXTURE.format(**values))
    test = ns.root / "tests" / "rules" / f"test_{function}.py"
    test.write_text(TEST.format(**values))
    print(f"wrote {module}\nwrote {fixture}\nwrote {test}")
    if not ns.module:
        print(f"now add `{function},` to the import list in src/robotdesc/rules/catalog.py")
    print("then write the check, and: python -m robotdesc.rules.docs > docs/rules.md && "
          "python -m robotdesc.rules.docs --index")
    return 0


if __name__ == "__main__":
    sys.exit(main())
