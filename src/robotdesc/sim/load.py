"""Read a description for simulation: expand, parse, and set up mesh resolution."""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any, Mapping

from robotdesc.expansion import ExpandOptions, expand_file
from robotdesc.expansion.packages import package_lookup
from robotdesc.model.elements import Robot
from robotdesc.sim.meshes import MeshAssets


@dataclass(frozen=True, eq=False)
class SimInput:
    """A parsed robot and the meshes it refers to.

    Attributes:
        robot: the strictly parsed robot.
        meshes: resolves `<mesh>` references through robotdesc's package resolver.
    """

    robot: Robot
    meshes: MeshAssets


def load_sim_input(path: str, args: Mapping[str, str] | None = None,
                   expand_options: Any = None) -> SimInput:
    """Expand (when xacro) and parse `path`; meshes resolve as the expansion's packages do.

    Raises:
        InputError: the file could not be expanded or parsed.
    """
    from robotdesc.model.parse import parse_urdf

    options = expand_options or ExpandOptions()
    expanded = expand_file(path, dict(args or {}), options=options)
    robot = parse_urdf(expanded.xml, expanded.source, expanded.files)
    known = {package.name: package.path for package in expanded.packages}
    return SimInput(robot, mesh_assets_for(expanded.source, options, known))


def mesh_assets_for(source: str, expand_options: Any = None,
                    known: Mapping[str, str] | None = None) -> MeshAssets:
    """Mesh resolution for a description file: packages found like the expansion finds them.

    Args:
        source: the description file.
        expand_options: `ExpandOptions` (its package paths and map are searched first).
        known: packages already resolved (name -> directory).
    """
    paths = tuple(getattr(expand_options, "package_paths", ()) or ())
    mapping = tuple(getattr(expand_options, "package_map", ()) or ())
    search = package_lookup(source, paths, mapping)
    resolved = dict(known or {})

    def find_package(name: str) -> str | None:
        return resolved[name] if name in resolved else search(name)

    return MeshAssets(find_package, os.path.dirname(os.path.abspath(source)))
