"""Which links move, which is the root, and whether a description is meant for dynamics.

Pure functions of the model; shared by the inertia rules, the mesh rules and the inertia
command.
"""

from __future__ import annotations

from robotdesc.model.elements import Joint, Link, Robot
from robotdesc.model.tree import connected_roots, parent_joint_of


def is_moving(link: Link, parents: dict[str, Joint]) -> bool:
    """The link is the child of a joint that is not fixed."""
    joint = parents.get(link.name)
    return joint is not None and joint.type != "fixed"


def root_links(robot: Robot) -> list[Link]:
    """Links that are no joint's child but are some joint's parent (or the only link)."""
    roots = connected_roots(robot)
    if not roots and len(robot.links) == 1:
        roots = list(robot.links)
    return roots


def has_mass(link: Link) -> bool:
    """The link declares a positive mass."""
    return link.inertial is not None and link.inertial.mass is not None \
        and link.inertial.mass > 0


def mass_of(link: Link) -> float:
    """The link's declared mass (kg); 0 when it has none or it is unreadable."""
    if link.inertial is None or link.inertial.mass is None:
        return 0.0
    return link.inertial.mass


def is_dynamics_model(robot: Robot) -> bool:
    """The description is meant for dynamics: at least one moving link declares a mass.

    A purely kinematic description (for a viewer or a planner) declares none; the rules
    about missing inertia do not apply to it.
    """
    parents = parent_joint_of(robot)
    return any(is_moving(link, parents) and has_mass(link) for link in robot.links)


def link_element(link: Link) -> str:
    """The stable element name of a link's inertial."""
    return f"link:{link.name}/inertial"
