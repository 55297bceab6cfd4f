"""A short summary of a `Robot` for `repr()` and Jupyter: counts, mass, DoF and the top of
its kinematic tree; never the whole model (a large robot's full repr runs to megabytes).

Plain functions over the model's attributes (no import of `elements`, which imports this);
the tree is `model/tree.py`'s.
"""

from __future__ import annotations

import html
from typing import TYPE_CHECKING

from robotdesc.model.tree import children_of, roots

if TYPE_CHECKING:  # elements imports this module at run time
    from robotdesc.model.elements import Robot

#: Links shown in the tree of the HTML summary, and levels below the root.
TREE_LINKS = 12
TREE_DEPTH = 3


def total_mass(robot: Robot) -> float:
    """The sum of the declared link masses (kg); links without a mass count 0."""
    return float(sum(link.inertial.mass for link in robot.links
                     if link.inertial is not None and link.inertial.mass is not None))


def degrees_of_freedom(robot: Robot) -> int:
    """The number of independently moving joints: not fixed, not a mimic of another.

    A floating joint counts 6, a planar joint 3, every other moving joint 1.
    """
    per_type = {"fixed": 0, "floating": 6, "planar": 3}
    return sum(per_type.get(joint.type, 1) for joint in robot.joints if joint.mimic is None)


def root_links(robot: Robot) -> list[str]:
    """Links that are no joint's child, in document order."""
    return [link.name for link in roots(robot)]


def tree_lines(robot: Robot, max_links: int = TREE_LINKS, max_depth: int = TREE_DEPTH) -> list[str]:
    """The top of the tree as indented lines (`└ joint (type) → link`), cut at `max_links`
    lines and `max_depth` levels, saying how many links were left out."""
    below = children_of(robot)
    lines: list[str] = []
    shown = 0

    def walk(link: str, depth: int, seen: set[str]) -> None:
        nonlocal shown
        for joint in below.get(link, []):
            if shown >= max_links or joint.child in seen:
                return
            lines.append(f"{'  ' * depth}└ {joint.name} ({joint.type}) → {joint.child}")
            shown += 1
            if depth + 1 < max_depth:
                walk(joint.child, depth + 1, seen | {joint.child})

    for root in root_links(robot):
        if shown >= max_links:
            break
        lines.append(root)
        shown += 1
        walk(root, 1, {root})
    hidden = len(robot.links) - len(lines)  # each line shows one link
    if hidden > 0:
        lines.append(f"… {hidden} more link{'s' if hidden != 1 else ''}")
    return lines


def robot_repr(robot: Robot) -> str:
    """`<Robot 'name': 246 links, 245 joints, 16.3 kg, 9 DoF, from engineer.urdf.xacro>`."""
    source = robot.source.replace("\\", "/").rsplit("/", 1)[-1] if robot.source else ""
    return (f"<Robot {robot.name!r}: {len(robot.links)} links, {len(robot.joints)} joints, "
            f"{total_mass(robot):.3g} kg, {degrees_of_freedom(robot)} DoF"
            + (f", from {source}" if source else "") + ">")


def robot_html(robot: Robot) -> str:
    """A small HTML summary: a table of the counts and the top of the tree."""
    moving = sum(1 for joint in robot.joints if joint.type != "fixed")
    rows = [("name", robot.name), ("source", robot.source or "-"),
            ("links", str(len(robot.links))),
            ("joints", f"{len(robot.joints)} ({moving} moving)"),
            ("mass", f"{total_mass(robot):.4g} kg"),
            ("degrees of freedom", str(degrees_of_freedom(robot))),
            ("root", ", ".join(root_links(robot)) or "-")]
    body = "".join(f"<tr><th style='text-align:left'>{html.escape(k)}</th>"
                   f"<td style='text-align:left'>{html.escape(v)}</td></tr>" for k, v in rows)
    tree = html.escape("\n".join(tree_lines(robot)))
    return (f"<div class='robotdesc-robot'><table>{body}</table>"
            f"<details><summary>kinematic tree (top)</summary><pre>{tree}</pre></details></div>")
