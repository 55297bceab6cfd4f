"""Mimic rules (J2xx): a `<mimic>` must follow an existing, compatible, non-circular joint."""

from __future__ import annotations

from collections.abc import Iterator

from robotdesc.diagnostics import Finding, Severity
from robotdesc.model.elements import Joint, Robot
from robotdesc.model.tree import mimicking
from robotdesc.rules.registry import RuleContext, rule
from robotdesc.source import Provenance

FAMILY = "mimic"

#: What a joint moves along: joints of the same motion can follow each other.
_MOTION = {"revolute": "rotation", "continuous": "rotation", "prismatic": "translation"}


@rule("J201", "mimic-target-missing", family=FAMILY, severity=Severity.ERROR)
def mimic_target_missing(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a `<mimic joint=...>` that names no joint of the robot.

    Why is this bad?
    The joint has nothing to follow: MoveIt and Pinocchio reject the model, Gazebo's mimic
    plugins log an error and leave the joint free.

    Example
    ```xml
    <robot name="gripper">
      <link name="palm"/><link name="left"/><link name="right"/>
      <joint name="left_finger" type="prismatic">
        <parent link="palm"/><child link="left"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
      <joint name="right_finger" type="prismatic">
        <parent link="palm"/><child link="right"/><mimic joint="left_fingr"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="gripper">
      <link name="palm"/><link name="left"/><link name="right"/>
      <joint name="left_finger" type="prismatic">
        <parent link="palm"/><child link="left"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
      <joint name="right_finger" type="prismatic">
        <parent link="palm"/><child link="right"/><mimic joint="left_finger"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
    </robot>
    ```
    """
    names = {joint.name for joint in robot.joints}
    for joint, target in mimicking(robot):
        if target not in names:
            yield Finding(f"joint '{joint.name}' mimics joint '{target}', which is not defined",
                          _mimic_where(joint), f"joint:{joint.name}")


@rule("J202", "mimic-of-itself", family=FAMILY, severity=Severity.ERROR)
def mimic_of_itself(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a joint whose `<mimic>` names the joint itself.

    Why is this bad?
    `q = multiplier * q + offset` is not a constraint anyone can satisfy or use; consumers
    reject it or loop. Usually a copy-paste slip in a macro.

    Example
    ```xml
    <robot name="gripper">
      <link name="palm"/><link name="left"/>
      <joint name="left_finger" type="prismatic">
        <parent link="palm"/><child link="left"/><mimic joint="left_finger"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="gripper">
      <link name="palm"/><link name="left"/>
      <joint name="left_finger" type="prismatic">
        <parent link="palm"/><child link="left"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
    </robot>
    ```
    """
    for joint, target in mimicking(robot):
        if target == joint.name:
            yield Finding(f"joint '{joint.name}' mimics itself",
                          _mimic_where(joint), f"joint:{joint.name}")


@rule("J203", "mimic-type-mismatch", family=FAMILY, severity=Severity.WARNING)
def mimic_type_mismatch(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a mimic joint that cannot follow its target: either of them is not a revolute,
    continuous or prismatic joint, or one rotates while the other translates.

    Why is this bad?
    A mimic couples one joint coordinate to another. A fixed, floating or planar joint has
    no single coordinate to couple, and mixing radians with metres is almost always a
    mistake (a gripper finger following the wrong joint). Pinocchio and MoveIt reject
    mimics of incompatible joints.

    Example
    ```xml
    <robot name="gripper">
      <link name="palm"/><link name="left"/><link name="right"/>
      <joint name="left_finger" type="fixed"><parent link="palm"/><child link="left"/></joint>
      <joint name="right_finger" type="prismatic">
        <parent link="palm"/><child link="right"/><mimic joint="left_finger"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="gripper">
      <link name="palm"/><link name="left"/><link name="right"/>
      <joint name="left_finger" type="prismatic">
        <parent link="palm"/><child link="left"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
      <joint name="right_finger" type="prismatic">
        <parent link="palm"/><child link="right"/><mimic joint="left_finger"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
    </robot>
    ```
    """
    joints: dict[str, Joint] = {}
    for joint in robot.joints:
        joints.setdefault(joint.name, joint)
    for joint, target_name in mimicking(robot):
        target = joints.get(target_name)
        if target is None or target is joint:
            continue
        mine, theirs = _MOTION.get(joint.type), _MOTION.get(target.type)
        if mine is None or theirs is None or mine != theirs:
            yield Finding(f"{joint.type} joint '{joint.name}' mimics {target.type} joint "
                          f"'{target.name}'", _mimic_where(joint),
                          f"joint:{joint.name}")


@rule("J204", "mimic-cycle", family=FAMILY, severity=Severity.ERROR)
def mimic_cycle(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds joints that mimic each other in a circle (a mimics b, b mimics a).

    Reported once per circle, at its first joint in document order. A joint mimicking
    itself is reported by `mimic-of-itself`.

    Why is this bad?
    No joint in the circle is free, so none of their positions is defined. Consumers that
    resolve mimic chains loop or reject the model.

    Example
    ```xml
    <robot name="gripper">
      <link name="palm"/><link name="left"/><link name="right"/>
      <joint name="left_finger" type="prismatic">
        <parent link="palm"/><child link="left"/><mimic joint="right_finger"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
      <joint name="right_finger" type="prismatic">
        <parent link="palm"/><child link="right"/><mimic joint="left_finger"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="gripper">
      <link name="palm"/><link name="left"/><link name="right"/>
      <joint name="left_finger" type="prismatic">
        <parent link="palm"/><child link="left"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
      <joint name="right_finger" type="prismatic">
        <parent link="palm"/><child link="right"/><mimic joint="left_finger"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
    </robot>
    ```
    """
    follows: dict[str, str] = {}
    first: dict[str, Joint] = {}
    for joint, target in mimicking(robot):
        follows.setdefault(joint.name, target)
        first.setdefault(joint.name, joint)
    order = {joint.name: i for i, joint in reversed(list(enumerate(robot.joints)))}
    done: set[str] = set()
    for joint in robot.joints:
        if joint.name in done or joint.name not in follows:
            continue
        path: list[str] = []
        on_path: set[str] = set()
        name: str | None = joint.name
        while name is not None and name not in done and name not in on_path:
            path.append(name)
            on_path.add(name)
            name = follows.get(name)
        if name is not None and name in on_path:
            circle = path[path.index(name):]
            if len(circle) > 1:
                head = first[min(circle, key=lambda n: order.get(n, 0))]
                yield Finding("joints mimic each other in a circle: "
                              + " -> ".join(f"'{n}'" for n in (*circle, circle[0])),
                              _mimic_where(head), f"joint:{head.name}")
        done.update(path)


def _mimic_where(joint: Joint) -> Provenance | None:
    """Where the joint's `<mimic>` is written, else the joint."""
    return (joint.mimic.where if joint.mimic is not None else None) or joint.where
