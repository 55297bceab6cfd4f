"""Every rule: imports each rule module (each registers its rules, see registry) and answers
for the whole set."""

from robotdesc.rules import (  # noqa: F401
    budget,
    consumers,
    gazebo,
    inertia,
    inertia_meshes,
    joints,
    kinematics,
    materials,
    meshes,
    meta,
    mimic,
    paths,
    ros2,
    self_collision,
    sim,
    structure,
    transmissions,
    vocabulary,
    xacro,
    xacro_inputs,
)
from robotdesc.rules.registry import Rule, find_registered, registered_rules


def all_rules() -> list[Rule]:
    """Every rule, sorted by code."""
    return registered_rules()


def get_rule(code_or_name: str) -> Rule | None:
    """The rule with this code (case-insensitive) or kebab-case name, or None."""
    return find_registered(code_or_name)
