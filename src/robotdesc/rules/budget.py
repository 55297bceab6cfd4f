"""Mass budget (B1xx): the robot's total declared mass against the mass it should have."""

from __future__ import annotations

from collections.abc import Iterator

from robotdesc.diagnostics import Finding, Severity
from robotdesc.inertia.links import has_mass
from robotdesc.model.elements import Robot
from robotdesc.rules.registry import RuleContext, rule

FAMILY = "budget"


@rule("B101", "mass-budget", family=FAMILY, severity=Severity.WARNING, needs=("meshes",))
def mass_budget(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a robot whose links' declared masses do not add up to the expected total
    (`[tool.robotdesc.meshes] expected-mass`, in kg, within `mass-tolerance`, 5% by default).

    Without an expected mass in the config, the rule checks nothing. It reads the mesh
    settings, which is why it declares that it needs meshes; it reads no mesh file.

    Why is this bad?
    The robot on the scale is the ground truth. A total that misses it points to a link
    whose mass is wrong (a unit slip, a copied value, a forgotten part), and a simulated
    robot of the wrong weight loads its motors and its contacts wrongly. The Engineer
    robot's authors weighed 16.3 kg.

    Example
    ```xml
    <!-- pyproject.toml: [tool.robotdesc.meshes] expected-mass = 16.3 -->
    <robot name="engineer">
      <link name="chassis"><inertial><mass value="9.8"/>...</inertial></link>
      <link name="arm"><inertial><mass value="3.3"/>...</inertial></link>
      <!-- 13.1 kg declared: the gripper and the batteries were forgotten -->
    </robot>
    ```

    Use instead (every part's mass declared, or the expectation corrected):
    ```xml
    <!-- pyproject.toml: [tool.robotdesc.meshes] expected-mass = 16.3 -->
    <robot name="engineer">
      <link name="chassis"><inertial><mass value="9.8"/>...</inertial></link>
      <link name="arm"><inertial><mass value="3.3"/>...</inertial></link>
      <link name="gripper"><inertial><mass value="0.9"/>...</inertial></link>
      <link name="batteries"><inertial><mass value="2.3"/>...</inertial></link>
    </robot>
    ```
    """
    if ctx.meshes is None:
        return
    settings = ctx.meshes.settings
    expected = settings.expected_mass
    if expected is None:
        return
    masses = [(link.inertial.mass, link.name) for link in robot.links
              if has_mass(link) and link.inertial is not None and link.inertial.mass is not None]
    total = sum(mass for mass, _ in masses)
    difference = total - expected
    if abs(difference) <= settings.mass_tolerance * expected:
        return
    heaviest = ", ".join(f"{name} {mass:.3g} kg" for mass, name in sorted(masses, reverse=True)[:3])
    yield Finding(f"robot '{robot.name}': its links declare {total:.4g} kg in total, "
                  f"{'more' if difference > 0 else 'less'} than the expected {expected:g} kg by "
                  f"{abs(difference):.3g} kg ({100 * abs(difference) / expected:.3g}%, tolerance "
                  f"{100 * settings.mass_tolerance:.3g}%)"
                  + (f"; heaviest: {heaviest}" if heaviest else ""),
                  robot.where, f"robot:{robot.name}")
