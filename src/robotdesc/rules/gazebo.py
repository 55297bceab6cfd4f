"""Gazebo rules (G): `<gazebo>` extension blocks must refer to something that exists."""

from __future__ import annotations

from collections.abc import Iterator

from robotdesc.diagnostics import Finding, Severity
from robotdesc.model.elements import Robot
from robotdesc.rules.registry import RuleContext, rule

FAMILY = "gazebo"


@rule("G101", "gazebo-reference-missing", family=FAMILY, severity=Severity.WARNING)
def gazebo_reference_missing(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a `<gazebo reference=...>` block whose reference names neither a link nor a
    joint of the robot.

    Why is this bad?
    Gazebo's URDF converter silently drops the block: the friction, material, sensor or
    plugin it carries never reaches the simulation. Usually a link renamed without its
    `<gazebo>` block, or a reference written with a prefix the macro did not apply.

    Example
    ```xml
    <robot name="rover">
      <link name="base_link"/>
      <gazebo reference="base">
        <material>Gazebo/Grey</material>
      </gazebo>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="rover">
      <link name="base_link"/>
      <gazebo reference="base_link">
        <material>Gazebo/Grey</material>
      </gazebo>
    </robot>
    ```
    """
    names = {link.name for link in robot.links} | {joint.name for joint in robot.joints}
    for block in robot.gazebo:
        if block.reference is not None and block.reference not in names:
            yield Finding(f"<gazebo reference=\"{block.reference}\"> names neither a link nor "
                          "a joint", block.where, f"gazebo:{block.reference}")
