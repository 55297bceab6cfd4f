"""Mesh files of a robot, found with robotdesc's own package resolver (never a ROS lookup)."""

from __future__ import annotations

import functools
import os
from collections.abc import Callable, Sequence

from robotdesc.model.elements import MeshRef, Robot

PackageLookup = Callable[[str], "str | None"]


def package_lookup(origin: str, package_paths: Sequence[str] = (),
                   package_map: Sequence[tuple[str, str]] = ()) -> PackageLookup:
    """A `find_package(name) -> folder or None` using the expansion's resolver chain.

    Args:
        origin: the description file (its enclosing package and workspace are searched).
        package_paths: `--package-path` folders, searched first.
        package_map: explicit (package, folder) pairs from the config.
    """
    from robotdesc.expansion.packages import PackageResolver, PackageResolverConfig

    resolver = PackageResolver(PackageResolverConfig.from_environment(
        origin, tuple(package_paths), tuple(package_map)))

    @functools.lru_cache(maxsize=None)
    def find(name: str) -> str | None:
        found = resolver.find(name)
        return found.path if found else None

    return find


def mesh_resolver(robot: Robot, find_package: PackageLookup) -> Callable[[MeshRef], str | None]:
    """A function mapping each `<mesh>` of `robot` to its resolved file, or None.

    Relative filenames are taken from the folder of the file that wrote the `<mesh>`.
    """
    from robotdesc.mesh.resolve import resolve_mesh

    def resolve(mesh: MeshRef) -> str | None:
        written_in = mesh.where.span.path if mesh.where is not None else robot.source
        base = os.path.dirname(os.path.abspath(written_in or "."))
        found = resolve_mesh(mesh.filename, base_dir=base, find_package=find_package)
        return found.path

    return resolve
