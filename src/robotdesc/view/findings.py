"""Attach lint findings to links, so that a view can highlight them and a report group them.

A diagnostic's `element` names what it is about: `link:NAME[/...]` belongs to that link,
`joint:NAME` to the joint's child link and `gazebo:NAME` to the link it references; anything
else (robot-wide, transmissions) belongs to no link.
"""

from __future__ import annotations

from collections.abc import Iterable

from robotdesc.diagnostics import Diagnostic
from robotdesc.model.elements import Robot


def link_of(element: str, robot: Robot) -> str | None:
    """The name of the link a diagnostic's `element` is about, or None."""
    kind, _, rest = element.partition(":")
    if kind in ("link", "gazebo"):
        names = {link.name for link in robot.links}
        if rest in names:
            return rest
        candidates = [n for n in names if rest.startswith(n + "/")]
        return max(candidates, key=len) if candidates else None
    if kind == "joint":
        joint = robot.joint(rest)
        return joint.child if joint is not None and robot.link(joint.child) else None
    return None


def findings_by_link(robot: Robot, diagnostics: Iterable[Diagnostic]
                     ) -> tuple[dict[str, list[Diagnostic]], list[Diagnostic]]:
    """Split diagnostics into per-link lists (document order of links) and the rest."""
    per_link: dict[str, list[Diagnostic]] = {}
    others: list[Diagnostic] = []
    for diagnostic in diagnostics:
        name = link_of(diagnostic.element, robot)
        if name is None:
            others.append(diagnostic)
        else:
            per_link.setdefault(name, []).append(diagnostic)
    order = {link.name: i for i, link in enumerate(robot.links)}
    return dict(sorted(per_link.items(), key=lambda item: order.get(item[0], 0))), others
