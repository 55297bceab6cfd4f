"""Imports every rule module so that each registers its rules (see registry)."""

from robotdesc.rules import (  # noqa: F401
    gazebo,
    joints,
    materials,
    meta,
    mimic,
    paths,
    structure,
    transmissions,
    xacro,
)
