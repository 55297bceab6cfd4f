"""Imports every rule module so that each registers its rules (see registry)."""

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
    sim,
    structure,
    transmissions,
    vocabulary,
    xacro,
    xacro_inputs,
)
