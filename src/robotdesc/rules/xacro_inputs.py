"""Xacro input rules (X1xx): arguments and environment the expansion used differently than
the user meant. The facts come from the expansion (`ExpansionFacts.notes`)."""

from __future__ import annotations

from collections.abc import Iterator

from robotdesc.diagnostics import Finding, Severity
from robotdesc.model.elements import Robot
from robotdesc.rules.registry import RuleContext, rule
from robotdesc.source import Provenance

FAMILY = "xacro"


def _notes(ctx: RuleContext, kind: str) -> Iterator[Finding]:
    for note in ctx.expansion.notes:
        if note.kind == kind:
            yield Finding(note.message, Provenance(note.span), f"{kind}:{note.subject}")


@rule("X102", "unknown-xacro-argument", family=FAMILY, severity=Severity.ERROR,
      needs=("expansion",))
def unknown_xacro_argument(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a `name:=value` argument that no `<xacro:arg>` of the description declares
    and no `$(arg name)` reads (xacro lets a file read an argument it never declares).

    Reported at the closest declared argument (named in the message), or at the top file
    when none is close.

    Why is this bad?
    Xacro ignores an argument nobody declared: a typo such as `main_track_wheel:=18` for
    `main_track_wheels` silently expands the robot with the default value, and the check
    passes on a robot other than the one you meant.

    Example
    ```xml
    <!-- robotdesc lint tracks.urdf.xacro main_track_wheel:=18 -->
    <robot name="tracks" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:arg name="main_track_wheels" default="12"/>
    </robot>
    ```

    Use instead (the declared name):
    ```xml
    <!-- robotdesc lint tracks.urdf.xacro main_track_wheels:=18 -->
    <robot name="tracks" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:arg name="main_track_wheels" default="12"/>
    </robot>
    ```
    """
    yield from _notes(ctx, "unknown-argument")


@rule("X103", "environment-not-passed", family=FAMILY, severity=Severity.WARNING,
      needs=("expansion",))
def environment_not_passed(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds an `$(optenv NAME default)` that used its default although NAME is set in
    your environment, because NAME was not passed with `--env NAME`.

    Reported at the line of the `$(optenv)`. The sandbox passes no environment variable
    to a xacro file unless you name it, so the robot checked is not the one your shell
    (or `ros2 launch`) would build.

    Why is this bad?
    The environment changes the robot silently: `JACKAL_LASER=1` adds a laser in your
    launch, but the sandboxed expansion used the default `0`, so the laser was never
    checked. Passing the variable makes the check see the same robot.

    Example
    ```xml
    <!-- JACKAL_LASER=1 robotdesc lint jackal.urdf.xacro -->
    <robot name="jackal" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:if value="$(optenv JACKAL_LASER 0)"><link name="laser"/></xacro:if>
    </robot>
    ```

    Use instead (name the variable):
    ```xml
    <!-- JACKAL_LASER=1 robotdesc lint --env JACKAL_LASER jackal.urdf.xacro -->
    <robot name="jackal" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:if value="$(optenv JACKAL_LASER 0)"><link name="laser"/></xacro:if>
    </robot>
    ```
    """
    yield from _notes(ctx, "env-not-passed")
