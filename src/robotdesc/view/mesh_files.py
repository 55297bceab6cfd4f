"""Find the file a `<mesh>` names, the way the lint rules do (package resolver chain, relative
paths from the file that holds the element), without computing any mass properties."""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence

from robotdesc.expansion.packages import enclosing_package, package_lookup
from robotdesc.mesh.resolve import MeshResolution, resolve_mesh
from robotdesc.model.elements import MeshRef, Robot

PackageLookup = Callable[[str], "str | None"]


class MeshFiles:
    """Resolves the mesh references of one robot (answers remembered).

    Args:
        robot: the model (its `source` is the fallback base directory).
        find_package: package name -> root directory, or None when unknown.
        allow_absolute: accept absolute paths and `file://` URIs.
    """

    def __init__(self, robot: Robot, find_package: PackageLookup,
                 allow_absolute: bool = False) -> None:
        self._robot = robot
        self._find_package = find_package
        self._allow_absolute = allow_absolute
        self._roots: dict[str, str | None] = {}
        self._found: dict[tuple[str, str], MeshResolution] = {}

    @classmethod
    def for_robot(cls, robot: Robot, package_paths: Sequence[str] = (),
                  package_map: Sequence[tuple[str, str]] = (),
                  allow_absolute: bool = False) -> MeshFiles:
        """A resolver using the expansion's package chain, searched from `robot.source`."""
        find_package = package_lookup(robot.source or os.getcwd(), package_paths, package_map)
        return cls(robot, find_package, allow_absolute)

    def resolve(self, ref: MeshRef) -> MeshResolution:
        """Where `ref` leads, or why it leads nowhere."""
        base = self._base_dir(ref)
        key = (ref.filename, base)
        if key not in self._found:
            self._found[key] = resolve_mesh(ref.filename, base_dir=base,
                                            find_package=self._find_package,
                                            allow_absolute=self._allow_absolute,
                                            relative_root=self._package_root(base))
        return self._found[key]

    def _base_dir(self, ref: MeshRef) -> str:
        written_in = ref.where.span.path if ref.where else ""
        if written_in and os.path.isfile(written_in):
            return os.path.dirname(os.path.abspath(written_in))
        return os.path.dirname(os.path.abspath(self._robot.source or "."))

    def _package_root(self, directory: str) -> str | None:
        if directory not in self._roots:
            found = enclosing_package(directory)
            self._roots[directory] = str(found[1]) if found else None
        return self._roots[directory]
