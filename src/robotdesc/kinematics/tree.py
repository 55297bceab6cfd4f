"""Transitional: the kinematic tree moved to `robotdesc.model.tree` (one implementation).

Kept only because `robotdesc.srdf.matrix` still imports `robotdesc.kinematics.tree`; remove
this module once srdf imports `robotdesc.model.tree`. Nothing else may import it.
"""

from __future__ import annotations

from robotdesc.model.tree import (
    LIMITED_TYPES,
    MOVING_TYPES,
    adjacent_pairs,
    body_masses,
    body_of,
    children_of,
    fixed_group,
    has_collision,
    link_mass,
    parent_joint_of,
    tree_problem,
)

__all__ = ["LIMITED_TYPES", "MOVING_TYPES", "adjacent_pairs", "body_masses", "body_of",
           "children_of", "fixed_group", "has_collision", "link_mass", "parent_joint_of",
           "tree_problem"]
