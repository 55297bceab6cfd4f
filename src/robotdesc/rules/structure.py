"""Structure rules (S): the links and joints must form one tree with unique names."""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from robotdesc.diagnostics import Finding, Severity
from robotdesc.model import tree
from robotdesc.model.elements import Joint, Link, Robot
from robotdesc.rules.registry import RuleContext, rule

FAMILY = "structure"


@rule("S001", "empty-robot", family=FAMILY, severity=Severity.ERROR)
def empty_robot(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a robot description without a single link.

    Often the result of an expansion where every macro call was skipped (a misspelt
    argument in an `xacro:if`, a macro defined but never called).

    Why is this bad?
    URDF consumers refuse a robot without links; there is nothing to load, simulate or
    check.

    Example
    ```xml
    <robot name="arm">
      <!-- the only macro call sat in an xacro:if whose condition was false -->
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base_link"/>
    </robot>
    ```
    """
    if not robot.links:
        yield Finding(f"robot '{robot.name}' has no links", robot.where, f"robot:{robot.name}")


@rule("S101", "no-root-link", family=FAMILY, severity=Severity.ERROR)
def no_root_link(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a robot in which every link is the child of some joint, so no link is the root.

    Why is this bad?
    A URDF is a tree hanging from one root link. Without a root, parsers such as urdfdom
    reject the file ("No root link found"), and the joints necessarily form a cycle.

    Example
    ```xml
    <robot name="loop">
      <link name="a"/>
      <link name="b"/>
      <joint name="a_to_b" type="fixed"><parent link="a"/><child link="b"/></joint>
      <joint name="b_to_a" type="fixed"><parent link="b"/><child link="a"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="loop">
      <link name="a"/>
      <link name="b"/>
      <joint name="a_to_b" type="fixed"><parent link="a"/><child link="b"/></joint>
    </robot>
    ```
    """
    if not robot.links:
        return
    if not tree.roots(robot):
        yield Finding(f"robot '{robot.name}' has no root link: each of its "
                      f"{len(robot.links)} links is the child of a joint",
                      robot.where, f"robot:{robot.name}")


@rule("S102", "multiple-root-links", family=FAMILY, severity=Severity.ERROR)
def multiple_root_links(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a robot whose joints form more than one tree (more than one root link).

    Each root after the first (in document order) is reported. A link that no joint
    mentions at all is reported by `disconnected-link` instead.

    Why is this bad?
    A URDF must be a single tree. urdfdom rejects the file ("Two root links found"), and
    tools that pick one root silently drop the other tree.

    Example
    ```xml
    <robot name="two_trees">
      <link name="base"/><link name="arm"/>
      <link name="cart"/><link name="wheel"/>
      <joint name="base_arm" type="fixed"><parent link="base"/><child link="arm"/></joint>
      <joint name="cart_wheel" type="continuous">
        <parent link="cart"/><child link="wheel"/>
      </joint>
    </robot>
    ```

    Use instead (connect the trees):
    ```xml
    <robot name="two_trees">
      <link name="base"/><link name="arm"/>
      <link name="cart"/><link name="wheel"/>
      <joint name="base_arm" type="fixed"><parent link="base"/><child link="arm"/></joint>
      <joint name="cart_wheel" type="continuous">
        <parent link="cart"/><child link="wheel"/>
      </joint>
      <joint name="cart_base" type="fixed"><parent link="cart"/><child link="base"/></joint>
    </robot>
    ```
    """
    roots = _unique_links(tree.connected_roots(robot))
    if len(roots) > 1:
        names = ", ".join(f"'{link.name}'" for link in roots)
        for link in roots[1:]:
            yield Finding(f"link '{link.name}' is a second root: the robot has {len(roots)} "
                          f"root links ({names})", link.where, f"link:{link.name}")


@rule("S103", "kinematic-cycle", family=FAMILY, severity=Severity.ERROR)
def kinematic_cycle(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds joints that close a loop (a link that is, through joints, its own ancestor).

    Reported once per loop, at the first joint of the loop in document order.

    Why is this bad?
    URDF describes trees only; closed chains (parallel mechanisms, four-bar linkages) are
    not representable. Parsers reject the file or loop forever walking it. Model the loop
    open and close it with a simulator-specific constraint (e.g. a `<gazebo>` joint) or use
    mimic joints.

    Example
    ```xml
    <robot name="loop">
      <link name="base"/><link name="a"/><link name="b"/>
      <joint name="base_a" type="fixed"><parent link="base"/><child link="a"/></joint>
      <joint name="a_b" type="fixed"><parent link="a"/><child link="b"/></joint>
      <joint name="b_a" type="fixed"><parent link="b"/><child link="a"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="loop">
      <link name="base"/><link name="a"/><link name="b"/>
      <joint name="base_a" type="fixed"><parent link="base"/><child link="a"/></joint>
      <joint name="a_b" type="fixed"><parent link="a"/><child link="b"/></joint>
    </robot>
    ```
    """
    for joint in tree.self_joints(robot):
        yield Finding(f"joint '{joint.name}' connects link '{joint.parent}' to itself",
                      joint.where, f"joint:{joint.name}")
    for joint, members in tree.cycles(robot):
        yield Finding(f"joint '{joint.name}' closes a kinematic loop through links "
                      + ", ".join(f"'{name}'" for name in members),
                      joint.where, f"joint:{joint.name}")


@rule("S104", "link-with-two-parents", family=FAMILY, severity=Severity.ERROR)
def link_with_two_parents(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a link that is the child of more than one joint.

    Reported at each joint after the first that names the link as its child.

    Why is this bad?
    In a tree each link has exactly one parent joint. urdfdom rejects the file; other
    parsers keep one joint and silently drop the other.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="tool"/>
      <joint name="mount" type="fixed"><parent link="base"/><child link="tool"/></joint>
      <joint name="mount_again" type="fixed"><parent link="base"/><child link="tool"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="tool"/>
      <joint name="mount" type="fixed"><parent link="base"/><child link="tool"/></joint>
    </robot>
    ```
    """
    first_parent = tree.parent_joint_of(robot)
    for joint in robot.joints:
        if not joint.child:
            continue
        earlier = first_parent[joint.child]
        if earlier is not joint:
            yield Finding(f"link '{joint.child}' already has parent joint '{earlier.name}'; "
                          f"joint '{joint.name}' gives it a second parent",
                          joint.where, f"joint:{joint.name}")


@rule("S105", "disconnected-link", family=FAMILY, severity=Severity.ERROR)
def disconnected_link(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a link that no joint connects to the rest of the robot.

    Why is this bad?
    The link is a second root of the tree: urdfdom rejects the robot ("Two root links
    found"), and tools that tolerate it drop the link. Usually a joint was forgotten or
    names the link with a typo.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="tool"/><link name="camera"/>
      <joint name="mount" type="fixed"><parent link="base"/><child link="tool"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="tool"/><link name="camera"/>
      <joint name="mount" type="fixed"><parent link="base"/><child link="tool"/></joint>
      <joint name="camera_mount" type="fixed">
        <parent link="tool"/><child link="camera"/>
      </joint>
    </robot>
    ```
    """
    if len(_unique_links(robot.links)) < 2:
        return
    mentioned = tree.mentioned_links(robot)
    for link in _unique_links(robot.links):
        if link.name not in mentioned:
            yield Finding(f"link '{link.name}' is not connected to any joint",
                          link.where, f"link:{link.name}")


@rule("S106", "duplicate-link-name", family=FAMILY, severity=Severity.ERROR)
def duplicate_link_name(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a link whose name is already used by an earlier link.

    Why is this bad?
    Link names are the keys joints refer to. urdfdom rejects duplicates; other tools keep
    one of the two definitions (which one varies).

    Example
    ```xml
    <robot name="arm">
      <link name="base"/>
      <link name="base"/>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/>
    </robot>
    ```
    """
    seen: dict[str, Link] = {}
    for link in robot.links:
        earlier = seen.setdefault(link.name, link)
        if earlier is not link:
            yield Finding(f"link name '{link.name}' is already defined"
                          + (f" at {earlier.where}" if earlier.where else ""),
                          link.where, f"link:{link.name}")


@rule("S107", "duplicate-joint-name", family=FAMILY, severity=Severity.ERROR)
def duplicate_joint_name(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a joint whose name is already used by an earlier joint.

    Why is this bad?
    Controllers, transmissions and mimic joints refer to joints by name. urdfdom rejects
    duplicates; other tools keep one of them.

    Example
    ```xml
    <robot name="arm">
      <link name="a"/><link name="b"/><link name="c"/>
      <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
      <joint name="j" type="fixed"><parent link="b"/><child link="c"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="a"/><link name="b"/><link name="c"/>
      <joint name="a_b" type="fixed"><parent link="a"/><child link="b"/></joint>
      <joint name="b_c" type="fixed"><parent link="b"/><child link="c"/></joint>
    </robot>
    ```
    """
    seen: dict[str, Joint] = {}
    for joint in robot.joints:
        earlier = seen.setdefault(joint.name, joint)
        if earlier is not joint:
            yield Finding(f"joint name '{joint.name}' is already defined"
                          + (f" at {earlier.where}" if earlier.where else ""),
                          joint.where, f"joint:{joint.name}")


@rule("S108", "joint-references-missing-link", family=FAMILY, severity=Severity.ERROR)
def joint_references_missing_link(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a joint whose `<parent>` or `<child>` names no link (or is missing).

    Why is this bad?
    The joint cannot be placed in the tree; urdfdom rejects the file. Usually a typo or a
    link renamed without updating its joints.

    Example
    ```xml
    <robot name="arm">
      <link name="base_link"/><link name="tool"/>
      <joint name="mount" type="fixed"><parent link="base"/><child link="tool"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base_link"/><link name="tool"/>
      <joint name="mount" type="fixed"><parent link="base_link"/><child link="tool"/></joint>
    </robot>
    ```
    """
    links = {link.name for link in robot.links}
    for joint in robot.joints:
        for role, name in (("parent", joint.parent), ("child", joint.child)):
            if not name:
                message = f"joint '{joint.name}' has no <{role} link=...>"
            elif name not in links:
                message = f"joint '{joint.name}' {role} link '{name}' is not defined"
            else:
                continue
            yield Finding(message, joint.where, f"joint:{joint.name}")


@rule("S109", "names-differ-only-in-case", family=FAMILY, severity=Severity.WARNING)
def names_differ_only_in_case(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds two links (or two joints) whose names differ only in letter case.

    Reported at the later of the two.

    Why is this bad?
    Names that differ only in case are easy to confuse and clash where names become file
    names on case-insensitive file systems (exported meshes, SDF models, generated
    controller configs on macOS and Windows).

    Example
    ```xml
    <robot name="arm">
      <link name="Base"/><link name="base"/>
      <joint name="mount" type="fixed"><parent link="Base"/><child link="base"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base_mount"/><link name="base"/>
      <joint name="mount" type="fixed"><parent link="base_mount"/><child link="base"/></joint>
    </robot>
    ```
    """
    for kind, names in (("link", [(l.name, l.where) for l in robot.links]),
                        ("joint", [(j.name, j.where) for j in robot.joints])):
        seen: dict[str, str] = {}
        for name, where in names:
            folded = name.casefold()
            earlier = seen.setdefault(folded, name)
            if earlier != name:
                yield Finding(f"{kind} '{name}' differs from {kind} '{earlier}' only in case",
                              where, f"{kind}:{name}")


@rule("S110", "unreadable-value", family=FAMILY, severity=Severity.ERROR)
def unreadable_value(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds attribute values that cannot be read: numbers that are not numbers, vectors
    with the wrong count, and required values or names that are missing.

    Why is this bad?
    urdfdom and most other parsers reject the whole file on the first such value; the
    lenient ones read it as 0, which silently changes the robot.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/>
        <origin xyz="0 0.1"/>
        <limit lower="-1" upper="1" effort="${max_effort}" velocity="2"/>
      </joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/>
        <origin xyz="0 0.1 0"/>
        <limit lower="-1" upper="1" effort="30" velocity="2"/>
      </joint>
    </robot>
    ```
    """
    for issue in robot.value_issues:
        owner = issue.element.split("/", 1)[0]
        kind, _, name = owner.partition(":")
        prefix = f"{kind} '{name}': " if name else (f"{kind}: " if kind else "")
        yield Finding(prefix + issue.message, issue.where, issue.element)


def _unique_links(links: Iterable[Link]) -> list[Link]:
    seen: set[str] = set()
    unique: list[Link] = []
    for link in links:
        if link.name not in seen:
            seen.add(link.name)
            unique.append(link)
    return unique
