"""Mesh files of a robot, found with robotdesc's own package resolver (never a ROS lookup)."""

from __future__ import annotations

import os
from collections.abc import Callable

from robotdesc.expansion.packages import package_lookup
from robotdesc.mesh.resolve import resolve_mesh
from robotdesc.model.elements import MeshRef, Robot

__all__ = ["PackageLookup", "mesh_resolver", "package_lookup"]

PackageLookup = Callable[[str], "str | None"]


def mesh_resolver(robot: Robot, find_package: PackageLookup) -> Callable[[MeshRef], str | None]:
    """A function mapping each `<mesh>` of `robot` to its resolved file, or None.

    Relative filenames are taken from the folder of the file that wrote the `<mesh>`.
    """
    def resolve(mesh: MeshRef) -> str | None:
        written_in = mesh.where.span.path if mesh.where is not None else robot.source
        base = os.path.dirname(os.path.abspath(written_in or "."))
        found = resolve_mesh(mesh.filename, base_dir=base, find_package=find_package)
        return found.path

    return resolve
