"""The files a command read, gathered for the output writer (`robotdesc.output`), which
refuses to write over any of them: the description, the files its expansion read, the
package.xml of every package it used, the config, and the meshes the robot references."""

from __future__ import annotations

import os
from collections.abc import Iterable, Sequence

from robotdesc.expansion.packages import enclosing_package
from robotdesc.expansion.result import Expanded
from robotdesc.mesh.locate import MeshLocator, PackageLookup
from robotdesc.model.elements import MeshRef, Robot
from robotdesc.output import RunInputs


def description_inputs(source: str | None, config_path: str | None = None) -> RunInputs:
    """The inputs known before any work: the description and its config (with the
    package.xml of the package holding the description)."""
    inputs = RunInputs().adding([source], "the description being read")
    inputs = inputs.adding([config_path], "the robotdesc config read")
    if source:
        found = enclosing_package(os.path.dirname(os.path.abspath(source)))
        if found is not None:
            inputs = inputs.adding([os.path.join(found[1], "package.xml")],
                                   f"package.xml of package '{found[0]}'")
    return inputs


def expansion_inputs(expanded: Expanded | None) -> RunInputs:
    """What an expansion read, and the package.xml of every package it resolved."""
    if expanded is None:
        return RunInputs()
    inputs = RunInputs().adding([expanded.source], "the description being read")
    inputs = inputs.adding([*expanded.files, *expanded.files_read],
                           "a file the expansion read")
    for package in expanded.packages:
        inputs = inputs.adding([os.path.join(package.path, "package.xml")],
                               f"package.xml of package '{package.name}'")
    return inputs


def inputs_locator(robot: Robot, package_paths: Sequence[str] = (),
                   package_map: Sequence[tuple[str, str]] = (),
                   find_package: PackageLookup | None = None) -> MeshLocator:
    """The mesh locator of `mesh_inputs` and `meshes_resolve`: absolute paths allowed, over
    the run's package lookup `find_package` when given (else one built from the settings)."""
    if find_package is not None:
        return MeshLocator(robot, find_package, allow_absolute=True)
    return MeshLocator.for_robot(robot, package_paths, package_map, allow_absolute=True)


def mesh_inputs(robot: Robot | None, package_paths: Sequence[str] = (),
                package_map: Sequence[tuple[str, str]] = (), *,
                locator: MeshLocator | None = None) -> RunInputs:
    """The files the robot's `<mesh>` elements name (found by the one mesh locator with
    absolute paths allowed: every file a reader of this robot might open is protected,
    whether or not the config allows it). `locator`: `inputs_locator`'s, when the caller
    has one."""
    if robot is None:
        return RunInputs()
    meshes = locator or inputs_locator(robot, package_paths, package_map)
    paths = [path for path in map(meshes.path, _mesh_refs(robot)) if path is not None]
    return RunInputs().adding(paths, "a mesh of the robot")


def meshes_resolve(robot: Robot | None, package_paths: Sequence[str] = (),
                   package_map: Sequence[tuple[str, str]] = (), *,
                   locator: MeshLocator | None = None) -> bool:
    """Whether every `<mesh>` of the robot names a file that exists (found as `mesh_inputs`
    finds them): a result that depends on a missing mesh is not cached."""
    if robot is None:
        return False
    meshes = locator or inputs_locator(robot, package_paths, package_map)
    return all(path is not None and os.path.isfile(path)
               for path in map(meshes.path, _mesh_refs(robot)))


def run_inputs(source: str | None = None, *, config_path: str | None = None,
               expanded: Expanded | None = None, robot: Robot | None = None,
               package_paths: Sequence[str] = (), package_map: Sequence[tuple[str, str]] = (),
               extra: Iterable[tuple[str | None, str]] = (),
               locator: MeshLocator | None = None) -> RunInputs:
    """Every input of a run on one description.

    Args:
        source: the description as given.
        config_path: the config file that applied.
        expanded: its expansion.
        robot: its parsed model (for the meshes).
        package_paths, package_map: the package settings the meshes resolve with.
        extra: more (path, what) pairs, e.g. a baseline read.
        locator: `inputs_locator`'s, when the caller has one (the run's package lookup).
    """
    inputs = description_inputs(source, config_path) + expansion_inputs(expanded) \
        + mesh_inputs(robot, package_paths, package_map, locator=locator)
    for path, what in extra:
        inputs = inputs.adding([path], what)
    return inputs


def _mesh_refs(robot: Robot) -> Iterable[MeshRef]:
    for link in robot.links:
        for element in link.visuals + link.collisions:
            if isinstance(element.geometry, MeshRef):
                yield element.geometry
