"""The files beside a description that the ROS 2 / Gazebo wiring rules (R1xx) judge, as plain
text: launch files, YAML, worlds, environment hooks, package.xml and CMakeLists.txt of the
packages a description belongs to and uses. The lint driver reads them
(`robotdesc.linting.package_reader`); rules only look at the text (launch files are read
with Python's `ast`, never run).
"""

from __future__ import annotations

from dataclasses import dataclass

#: File kinds (`PackageFile.kind`).
LAUNCH_PY, LAUNCH_XML, YAML, WORLD, HOOK, MANIFEST, CMAKE = (
    "launch.py", "launch.xml", "yaml", "world", "hook", "package.xml", "cmake")


@dataclass(frozen=True)
class PackageFile:
    """One file of a package, read as text (UTF-8, undecodable bytes replaced).

    Attributes:
        path: absolute path.
        kind: one of the kinds above.
        text: its contents.
    """

    path: str
    kind: str
    text: str


@dataclass(frozen=True)
class Package:
    """A ROS package: the folder holding a package.xml.

    Attributes:
        name: its name (package.xml `<name>`, else the folder's name).
        path: its root folder (absolute).
        files: the files of the kinds above found in it, in path order.
    """

    name: str
    path: str
    files: tuple[PackageFile, ...] = ()

    def of_kind(self, *kinds: str) -> tuple[PackageFile, ...]:
        return tuple(f for f in self.files if f.kind in kinds)


@dataclass(frozen=True)
class PackageFiles:
    """The packages of one lint target.

    Attributes:
        packages: the package holding the description first, then the packages its
            expansion resolved (`$(find ...)`, `package://`), each once.
        named: YAML files the description names itself (the `<parameters>` of a
            gz_ros2_control / gazebo_ros2_control plugin), read wherever they are.
    """

    packages: tuple[Package, ...] = ()
    named: tuple[PackageFile, ...] = ()

    def files(self, *kinds: str) -> tuple[PackageFile, ...]:
        """Every file of these kinds in every package (each path once), then the named ones."""
        seen: set[str] = set()
        found: list[PackageFile] = []
        for item in (*(f for p in self.packages for f in p.files), *self.named):
            if item.kind in kinds and item.path not in seen:
                seen.add(item.path)
                found.append(item)
        return tuple(found)

    def package(self, name: str) -> Package | None:
        return next((p for p in self.packages if p.name == name), None)
