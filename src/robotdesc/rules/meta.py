"""Meta rules (RD): findings about robotdesc's own use, emitted by the lint driver."""

from __future__ import annotations

from collections.abc import Iterator

from robotdesc.diagnostics import Finding, Severity
from robotdesc.model.elements import Robot
from robotdesc.rules.registry import RuleContext, rule

FAMILY = "meta"

#: The code the lint driver uses for a suppression comment that suppressed nothing.
UNUSED_SUPPRESSION = "RD001"


@rule(UNUSED_SUPPRESSION, "unused-suppression", family=FAMILY, severity=Severity.WARNING)
def unused_suppression(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds an inline suppression comment that suppresses nothing.

    A finding is suppressed by a comment `<!-- robotdesc: ignore CODE[, CODE] -->` on the
    line of the offending element's start tag or on the line just before it (in the xacro
    source, where the finding points). CODE is a rule code such as `J102`; several codes
    are separated by commas. This rule is emitted by the lint driver, not by a check of its
    own: a comment that matches no finding is reported here, so stale suppressions do not
    pile up.

    Why is this bad?
    A suppression that no longer matches a finding hides nothing today, but it will
    silently hide a new problem of that kind on that element tomorrow. It usually outlives
    a fix or a rename.

    Example
    ```xml
    <!-- robotdesc: ignore J102 -->
    <joint name="shoulder" type="revolute">
      <parent link="base"/><child link="arm"/>
      <limit lower="-1" upper="1" effort="30" velocity="2"/>
    </joint>
    ```

    Use instead (the joint has its limit; drop the comment):
    ```xml
    <joint name="shoulder" type="revolute">
      <parent link="base"/><child link="arm"/>
      <limit lower="-1" upper="1" effort="30" velocity="2"/>
    </joint>
    ```
    """
    return iter(())
