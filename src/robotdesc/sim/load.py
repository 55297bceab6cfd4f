"""Read a description for simulation: expand, parse, and set up mesh resolution."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from robotdesc.expansion import ExpandOptions, expand_file
from robotdesc.expansion.packages import package_lookup
from robotdesc.mesh.locate import MeshLocator
from robotdesc.model.elements import Robot
from robotdesc.sim.meshes import MeshAssets


@dataclass(frozen=True, eq=False)
class SimInput:
    """A parsed robot and the meshes it refers to.

    Attributes:
        robot: the strictly parsed robot.
        meshes: resolves `<mesh>` references as lint does (`robotdesc.mesh.locate`).
    """

    robot: Robot
    meshes: MeshAssets


def load_sim_input(path: str, args: Mapping[str, str] | None = None,
                   expand_options: ExpandOptions | None = None, *,
                   allow_absolute: bool = False) -> SimInput:
    """Expand (when xacro) and parse `path`; meshes resolve under the rules of lint.

    Args:
        path: the description file.
        args: xacro arguments.
        expand_options: the expansion's options (its package paths and map are searched
            for meshes too).
        allow_absolute: accept `file://` URIs and absolute mesh paths (the config's
            `[meshes] allow_absolute_paths`; off by default, as for lint).

    Raises:
        InputError: the file could not be expanded or parsed.
    """
    from robotdesc.model.parse import parse_urdf

    options = expand_options or ExpandOptions()
    expanded = expand_file(path, dict(args or {}), options=options)
    robot = parse_urdf(expanded.xml, expanded.source, expanded.files)
    known = {package.name: package.path for package in expanded.packages}
    search = package_lookup(expanded.source, options.package_paths, options.package_map)

    def find_package(name: str) -> str | None:
        """The packages the expansion used first, then the resolver chain."""
        return known[name] if name in known else search(name)

    return SimInput(robot, MeshAssets(MeshLocator(robot, find_package, allow_absolute)))
