"""Physics rules (D): the MuJoCo settle test as a lint rule. Opt-in (it simulates).

Off by default: select it with `--select D101` (or `D`, or its name) or `select` in the config.
MuJoCo (the optional `robotdesc[sim]` extra) is imported only when the rule runs.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Literal

from robotdesc.diagnostics import Finding, Severity
from robotdesc.mesh.locate import MeshLocator
from robotdesc.model.elements import Robot
from robotdesc.rules.registry import RuleContext, rule
from robotdesc.sim.scene import SceneOptions

FAMILY = "sim"


@dataclass(frozen=True)
class SettleRuleOptions:
    """Options of D101.

    Attributes:
        seconds: simulated time (s).
        drop_height: start this high above the ground (m).
        hold: "position" (servos hold the joints at neutral) or "passive".
    """

    seconds: float = 2.0
    drop_height: float = 0.05
    hold: Literal["position", "passive"] = "position"


@rule("D101", "fails-settle-test", family=FAMILY, severity=Severity.ERROR,
      options=SettleRuleOptions, needs=("meshes",), opt_in=True)
def fails_settle_test(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a link that makes the robot blow up or fall apart when dropped in MuJoCo.

    The robot is dropped from a small height onto a plane with its joints held at neutral
    by servos tuned to the links' mass and shape, and simulated for a few seconds. A finding
    names the link blamed by each failed check: the state became NaN, the energy grew
    instead of decaying, a joint ran away, or a joint limit or mimic constraint broke; or
    MuJoCo refused the link outright (a massless moving link, an impossible inertia).
    Opt-in (it runs a simulation) and needs MuJoCo: `pip install ".[sim]"`.

    Why is this bad?
    A model that explodes or falls apart on spawn cannot be simulated or controlled, and the
    usual way to find out is to launch Gazebo and look. The usual cause is an inertia wrong
    by a unit slip (kg*mm^2 written as kg*m^2): the link's written inertia is far below what
    its mass and shape imply, so any controller tuned to the real robot makes it unstable.

    Example
    ```xml
    <link name="wrist_roll_link">
      <inertial>
        <mass value="0.3"/>
        <inertia ixx="1.9e-10" ixy="0" ixz="0" iyy="1.9e-10" iyz="0" izz="1.35e-10"/>
      </inertial>
    </link>
    ```

    Use instead (the inertia of the link's geometry; `robotdesc inertia --suggest`):
    ```xml
    <link name="wrist_roll_link">
      <inertial>
        <mass value="0.3"/>
        <inertia ixx="0.000227" ixy="0" ixz="0" iyy="0.000227" iyz="0" izz="0.000135"/>
      </inertial>
    </link>
    ```
    """
    if ctx.meshes is None:  # run outside the lint driver without mesh access: cannot simulate
        return
    from robotdesc.sim.hold import HoldOptions
    from robotdesc.sim.meshes import MeshAssets
    from robotdesc.sim.run import SimOptions, settle_robot
    from robotdesc.sim.settle import SettleOptions

    options = ctx.options_as(SettleRuleOptions)
    meshes = MeshAssets(MeshLocator.with_settings(robot, ctx.meshes.find_package,
                                                  ctx.meshes.settings))
    settings = SimOptions(settle=SettleOptions(seconds=options.seconds,
                                               hold=HoldOptions(mode=options.hold)),
                          scene=SceneOptions(drop_height=options.drop_height))
    report = settle_robot(robot, meshes, settings)
    for check in report.failures:
        link = robot.link(check.link) if check.link else None
        where = link.where if link is not None else robot.where
        element = f"link:{check.link}" if check.link else "robot"
        yield Finding(f"settle test, {check.name} check"
                      + (f" at t={check.time:.3f} s" if check.time else "")
                      + f": {check.message}", where, element)
