"""Visual rules (V): materials referenced by visuals must be defined."""

from __future__ import annotations

from collections.abc import Iterator

from robotdesc.diagnostics import Finding, Severity
from robotdesc.model.elements import Material, Robot
from robotdesc.rules.registry import RuleContext, rule

FAMILY = "visual"


def _defines(material: Material) -> bool:
    return material.color is not None or material.texture is not None


@rule("V101", "undefined-material", family=FAMILY, severity=Severity.WARNING)
def undefined_material(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a visual whose `<material name=...>` has no color or texture of its own and
    names a material that is never defined with one.

    A material counts as defined when a robot-level `<material>` or any inline material of
    that name has a `<color>` or a `<texture>`.

    Why is this bad?
    The colour meant is lost: urdfdom accepts a material given by name alone (the
    definition may be elsewhere in the robot) and, finding none, leaves the visual without
    a colour, so viewers draw the link in a default one. Usually a material defined in a
    file that is not included, or a misspelt name.

    Example
    ```xml
    <robot name="arm">
      <link name="base">
        <visual>
          <geometry><box size="0.1 0.1 0.1"/></geometry>
          <material name="grey"/>
        </visual>
      </link>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>
      <link name="base">
        <visual>
          <geometry><box size="0.1 0.1 0.1"/></geometry>
          <material name="grey"/>
        </visual>
      </link>
    </robot>
    ```
    """
    defined = {m.name for m in robot.materials if _defines(m)}
    for link in robot.links:
        for visual in link.visuals:
            if visual.material is not None and _defines(visual.material):
                defined.add(visual.material.name)
    for link in robot.links:
        for index, visual in enumerate(link.visuals):
            material = visual.material
            if material is None or _defines(material) or not material.name:
                continue
            if material.name not in defined:
                yield Finding(f"link '{link.name}' visual uses material '{material.name}', "
                              "which is never defined with a color or texture",
                              material.where or visual.where,
                              f"link:{link.name}/visual[{index}]")
