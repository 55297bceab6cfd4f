"""The one mesh locator: where each `<mesh filename>` of a robot leads, under the rules of lint.

Every reader of meshes (the lint rules' mesh context, the viewer, the kinematics and
collision-matrix builders, the simulators, collision generation, the run's protected inputs)
finds files through a `MeshLocator`, so that a reference resolves the same everywhere:

- `package://pkg/file` through the package lookup (the expansion's resolver chain), and stays
  inside that package's root after symlinks;
- a relative filename from the folder of the file that WROTE the `<mesh>` element (a xacro
  file included from a subfolder, not the top file), and stays inside the package enclosing
  that folder, if any;
- `file://` URIs and absolute paths only when the policy allows them (the config's
  `[meshes] allow_absolute_paths`; off by default).

The checks themselves are `robotdesc.mesh.resolve.resolve_mesh` (pure apart from file-system
queries); this module only decides its inputs. Plain Python: no numpy.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass, field

from robotdesc.expansion.packages import enclosing_package, package_lookup
from robotdesc.mesh.resolve import MeshResolution, PackageLookup, resolve_mesh
from robotdesc.mesh.settings import MeshSettings
from robotdesc.model.elements import MeshRef, Robot

__all__ = ["MeshLocator", "PackageLookup"]


@dataclass(frozen=True, eq=False)
class MeshLocator:
    """Maps the `<mesh>` references of one robot to files (answers remembered).

    Attributes:
        robot: the model; its `source` is the base folder of a reference whose writing file
            is unknown or gone (no source: the current directory).
        find_package: package name -> root folder, or None when the package is unknown.
        allow_absolute: accept `file://` URIs and absolute paths (the config's
            `allow_absolute_paths`; off: such a description works only on its author's machine).
    """

    robot: Robot
    find_package: PackageLookup
    allow_absolute: bool = False
    _bases: dict[str, str] = field(default_factory=dict, init=False, repr=False)
    _roots: dict[str, str | None] = field(default_factory=dict, init=False, repr=False)
    _found: dict[tuple[str, str], MeshResolution] = field(default_factory=dict, init=False,
                                                           repr=False)

    @classmethod
    def for_robot(cls, robot: Robot, package_paths: Sequence[str] = (),
                  package_map: Sequence[tuple[str, str]] = (), *,
                  allow_absolute: bool = False, origin: str | None = None) -> MeshLocator:
        """A locator over the expansion's package resolver chain.

        Args:
            robot: the model.
            package_paths: `--package-path` folders, searched first.
            package_map: explicit (package, folder) pairs from the config.
            allow_absolute: accept `file://` URIs and absolute paths.
            origin: the file whose package and workspace are searched (default:
                `robot.source`, else the current directory).
        """
        find = package_lookup(origin or robot.source or os.getcwd(), tuple(package_paths),
                              tuple(package_map))
        return cls(robot, find, allow_absolute)

    @classmethod
    def with_settings(cls, robot: Robot, find_package: PackageLookup,
                      settings: MeshSettings) -> MeshLocator:
        """A locator under the config's mesh policy (`[meshes] allow_absolute_paths`)."""
        return cls(robot, find_package, settings.allow_absolute_paths)

    def locate(self, ref: MeshRef) -> MeshResolution:
        """Where `ref` leads (its real path, symlinks followed), or why it leads nowhere."""
        base = self.base_dir(ref)
        key = (ref.filename, base)
        found = self._found.get(key)
        if found is None:
            found = resolve_mesh(ref.filename, base_dir=base, find_package=self.find_package,
                                 allow_absolute=self.allow_absolute,
                                 relative_root=self.package_root(base))
            self._found[key] = found
        return found

    def path(self, ref: MeshRef) -> str | None:
        """The file `ref` leads to, or None when it does not resolve (a `MeshPath`)."""
        return self.locate(ref).path

    def base_dir(self, ref: MeshRef) -> str:
        """The absolute folder a relative filename is taken from: that of the file holding
        the `<mesh>` element (a xacro file for expanded input), else the robot's source's,
        else the current directory."""
        written_in = ref.where.span.path if ref.where is not None else ""
        found = self._bases.get(written_in)
        if found is None:
            if written_in and os.path.isfile(written_in):
                found = os.path.dirname(os.path.abspath(written_in))
            elif self.robot.source:
                found = os.path.dirname(os.path.abspath(self.robot.source))
            else:
                found = os.getcwd()
            self._bases[written_in] = found
        return found

    def package_root(self, folder: str) -> str | None:
        """The root of the package enclosing `folder` (a relative path stays inside it), or
        None when no package.xml is found above it."""
        if folder not in self._roots:
            found = enclosing_package(folder)
            self._roots[folder] = str(found[1]) if found else None
        return self._roots[folder]
