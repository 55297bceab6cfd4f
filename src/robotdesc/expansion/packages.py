"""Find ROS packages without ROS: a chain of resolvers, first hit wins.

The chain, in order: explicit `--package-path` directories and the config map
(`pkg = "dir"`), the package that encloses the file (walk up to package.xml), sibling
packages in the same workspace, `ROS_PACKAGE_PATH`, `AMENT_PREFIX_PATH` (share/<pkg>).
"""

from __future__ import annotations

import functools
import logging
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from robotdesc.errors import InputError
from robotdesc.expansion.result import ResolvedPackage

log = logging.getLogger(__name__)

#: The largest package.xml read (bytes).
_MAX_MANIFEST_BYTES = 1 << 20

#: Directories never searched for packages (build products, VCS, virtual environments).
_SKIP_DIRS = frozenset({"build", "install", "log", "node_modules", "__pycache__", "site-packages"})
#: How deep below a search root package.xml files are looked for.
_MAX_SEARCH_DEPTH = 6
_WORKSPACE_MARKERS = (".git", ".hg", ".catkin_workspace", ".colcon", "colcon.meta", ".catkin_tools")


@functools.lru_cache(maxsize=4096)
def read_package_name(package_xml: str) -> str | None:
    """The `<name>` of a package.xml, or None when it cannot be read.

    Parsed by the one guarded parser (no DTD, entities or network; at most 1 MiB).
    """
    from robotdesc.xml_input import XmlOptions, read_xml  # lxml: not for `robotdesc --help`

    try:
        root = read_xml(package_xml, XmlOptions(what="package.xml"),
                        max_bytes=_MAX_MANIFEST_BYTES)
    except InputError as exc:
        log.warning("%s: cannot read package manifest: %s", package_xml, exc)
        return None
    name = root.findtext("name")
    return name.strip() if name else None


def enclosing_package(path: str | Path) -> tuple[str, Path] | None:
    """The package that contains `path` (walking up to the nearest package.xml)."""
    here = Path(path).resolve()
    for folder in ([here] if here.is_dir() else []) + list(here.parents):
        manifest = folder / "package.xml"
        if manifest.is_file():
            name = read_package_name(str(manifest))
            return (name, folder) if name else None
    return None


def workspace_root(package_dir: Path) -> Path:
    """The workspace that holds a package: the nearest ancestor that looks like one.

    A workspace root holds a VCS or colcon/catkin marker, or is the parent of a `src/` folder
    holding the package. Falls back to the package's parent folder.
    """
    for folder in package_dir.parents:
        if folder.name == "src":
            return folder.parent
        if any((folder / marker).exists() for marker in _WORKSPACE_MARKERS):
            return folder
    return package_dir.parent


def crawl_packages(root: Path, max_depth: int = _MAX_SEARCH_DEPTH) -> dict[str, Path]:
    """Every package under `root` (not descending into a package), name -> folder.

    In an install space (`.../share/<folder>/package.xml`) the folder's name is a name of
    the package too, as for ament.

    The first folder found (sorted walk) wins when two packages share a name. Results are
    remembered for the life of the process (a lint run; packages do not appear mid-run).
    """
    return dict(_crawl_packages_cached(str(root), max_depth))


@functools.lru_cache(maxsize=256)
def _crawl_packages_cached(root_text: str, max_depth: int) -> tuple[tuple[str, Path], ...]:
    root = Path(root_text)
    found: dict[str, Path] = {}

    def visit(folder: Path, depth: int) -> None:
        # One directory listing per folder (os.scandir knows which entries are folders
        # without a stat each): the crawl of a workspace is on every cold expansion's path.
        try:
            with os.scandir(folder) as listing:
                entries = list(listing)
        except OSError:
            return
        names = {entry.name: entry for entry in entries}
        manifest = names.get("package.xml")
        if manifest is not None and _is_file(manifest):
            for name in _names_of(read_package_name(str(folder / "package.xml")), folder):
                found.setdefault(name, folder)
            return
        if depth >= max_depth or "CATKIN_IGNORE" in names or "COLCON_IGNORE" in names:
            return
        for child in sorted(entry.name for entry in entries if _is_dir(entry)):
            if child.startswith(".") or child in _SKIP_DIRS:
                continue
            visit(folder / child, depth + 1)

    if root.is_dir():
        visit(root, 0)
    return tuple(found.items())


def _is_file(entry: os.DirEntry[str]) -> bool:
    try:
        return entry.is_file()
    except OSError:
        return False


def _is_dir(entry: os.DirEntry[str]) -> bool:
    try:
        return entry.is_dir()
    except OSError:
        return False


def _names_of(name: str | None, folder: Path) -> tuple[str, ...]:
    """The names a package folder answers to: its package.xml name and, in an install space
    (`.../share/<folder>`), the folder's name, by which ament finds it (example-robot-data's
    package.xml says example_robot_descriptions)."""
    names: tuple[str, ...] = (name,) if name else ()
    if folder.parent.name == "share" and folder.name not in names:
        names += (folder.name,)
    return names


@dataclass(frozen=True)
class PackageResolverConfig:
    """Everything the resolver chain depends on (picklable: sent to the xacro worker).

    Attributes:
        origin: the file being expanded (its enclosing package and workspace are searched).
        package_paths: `--package-path` folders: a package, or a folder holding packages.
        package_map: explicit (name, folder) pairs from the config file.
        ros_package_path: the value of ROS_PACKAGE_PATH ("" to ignore it).
        ament_prefix_path: the value of AMENT_PREFIX_PATH ("" to ignore it).
    """

    origin: str
    package_paths: tuple[str, ...] = ()
    package_map: tuple[tuple[str, str], ...] = ()
    ros_package_path: str = ""
    ament_prefix_path: str = ""

    @classmethod
    def from_environment(cls, origin: str, package_paths: tuple[str, ...] = (),
                         package_map: tuple[tuple[str, str], ...] = ()) -> "PackageResolverConfig":
        return cls(str(Path(origin).resolve()), tuple(str(Path(p).resolve()) for p in package_paths),
                   tuple((name, str(Path(folder).resolve())) for name, folder in package_map),
                   os.environ.get("ROS_PACKAGE_PATH", ""), os.environ.get("AMENT_PREFIX_PATH", ""))


class PackageResolver:
    """The resolver chain. `find(name)` returns the first hit and remembers it."""

    def __init__(self, config: PackageResolverConfig,
                 known: Sequence[ResolvedPackage] | None = None) -> None:
        """Args:
            config: the settings of the chain.
            known: the result of `candidates()` computed elsewhere (the xacro worker gets
                it from the parent): `find` then reads no file and parses no manifest.
        """
        self.config = config
        self._resolved: dict[str, ResolvedPackage] = {}
        self._explicit: dict[str, tuple[Path, str]] | None = None
        self._workspace: dict[str, Path] | None = None
        self._ros_path: dict[str, Path] | None = None
        self._known: dict[str, ResolvedPackage] | None = None
        if known is None:
            self.enclosing = enclosing_package(config.origin)
        else:
            self._known = {}
            for package in known:
                self._known.setdefault(package.name, package)
            found = next((p for p in known if p.source == "enclosing"), None)
            self.enclosing = (found.name, Path(found.path)) if found else None

    @property
    def resolved(self) -> tuple[ResolvedPackage, ...]:
        """The packages found so far, in the order they were first asked for."""
        return tuple(self._resolved.values())

    def searched(self) -> tuple[str, ...]:
        """A short description of where the chain looks, for error messages."""
        places = [f"--package-path {p}" for p in self.config.package_paths]
        places += [f"config {name}={folder}" for name, folder in self.config.package_map]
        if self.enclosing:
            places.append(f"enclosing package {self.enclosing[0]}")
            places.append(f"workspace {workspace_root(self.enclosing[1])}")
        if self.config.ros_package_path:
            places.append("ROS_PACKAGE_PATH")
        if self.config.ament_prefix_path:
            places.append("AMENT_PREFIX_PATH")
        return tuple(places)

    def candidates(self) -> tuple[ResolvedPackage, ...]:
        """Every package `find` can return, crawling every source of the chain now.

        In the order of the chain (the first entry of a name is the one `find` returns);
        a folder answering to several names appears once per name. After this call, `find`
        reads no manifest (the crawls are remembered).
        """
        found: list[ResolvedPackage] = []
        for name, (path, source) in self._explicit_packages().items():
            found.append(ResolvedPackage(name, str(path), source))
        if self.enclosing:
            for name in _names_of(*self.enclosing):
                found.append(ResolvedPackage(name, str(self.enclosing[1]), "enclosing"))
            for name, path in self._workspace_packages().items():
                found.append(ResolvedPackage(name, str(path), "workspace"))
        for name, path in self._ros_path_packages().items():
            found.append(ResolvedPackage(name, str(path), "ROS_PACKAGE_PATH"))
        for prefix in filter(None, self.config.ament_prefix_path.split(os.pathsep)):
            share = Path(prefix) / "share"
            try:
                folders = sorted(p for p in share.iterdir() if p.is_dir())
            except OSError:
                continue
            found.extend(ResolvedPackage(p.name, str(p.resolve()), "AMENT_PREFIX_PATH")
                         for p in folders)
        return tuple(found)

    def find(self, name: str) -> ResolvedPackage | None:
        """The package called `name`, or None when no resolver knows it."""
        if name in self._resolved:
            return self._resolved[name]
        hit = self._known.get(name) if self._known is not None else self._search(name)
        if hit is not None:
            self._resolved[name] = hit
            log.info("package %s -> %s (from %s)", name, hit.path, hit.source)
        return hit

    def _search(self, name: str) -> ResolvedPackage | None:
        explicit = self._explicit_packages()
        if name in explicit:
            return ResolvedPackage(name, str(explicit[name][0]), explicit[name][1])
        if self.enclosing and name in _names_of(*self.enclosing):
            return ResolvedPackage(name, str(self.enclosing[1]), "enclosing")
        if self.enclosing:
            workspace = self._workspace_packages()
            if name in workspace:
                return ResolvedPackage(name, str(workspace[name]), "workspace")
        ros_path = self._ros_path_packages()
        if name in ros_path:
            return ResolvedPackage(name, str(ros_path[name]), "ROS_PACKAGE_PATH")
        for prefix in filter(None, self.config.ament_prefix_path.split(os.pathsep)):
            share = Path(prefix) / "share" / name
            if (share / "package.xml").is_file() or share.is_dir():
                return ResolvedPackage(name, str(share.resolve()), "AMENT_PREFIX_PATH")
        return None

    def _workspace_packages(self) -> dict[str, Path]:
        if self._workspace is None:
            self._workspace = crawl_packages(workspace_root(self.enclosing[1])) \
                if self.enclosing else {}
        return self._workspace

    def _ros_path_packages(self) -> dict[str, Path]:
        if self._ros_path is None:
            self._ros_path = {}
            for entry in filter(None, self.config.ros_package_path.split(os.pathsep)):
                for pkg, folder in crawl_packages(Path(entry)).items():
                    self._ros_path.setdefault(pkg, folder)
        return self._ros_path

    def _explicit_packages(self) -> dict[str, tuple[Path, str]]:
        if self._explicit is None:
            self._explicit = {}
            for folder in self.config.package_paths:
                for pkg, path in crawl_packages(Path(folder)).items():
                    self._explicit.setdefault(pkg, (path, "--package-path"))
            for pkg, folder in self.config.package_map:
                self._explicit.setdefault(pkg, (Path(folder), "config"))
        return self._explicit


def split_package_uri(uri: str) -> tuple[str, str, bool] | None:
    """Split `package://pkg/rel/path` into (pkg, rel/path, three_slashes).

    Returns None when `uri` is not a package URI. `package:///pkg/...` (three slashes, a common
    slip) is accepted and flagged.
    """
    if not uri.startswith("package://"):
        return None
    rest = uri[len("package://"):]
    three = rest.startswith("/")
    rest = rest.lstrip("/")
    pkg, _, rel = rest.partition("/")
    return pkg, rel, three


def package_lookup(origin: str, package_paths: Sequence[str] = (),
                   package_map: Sequence[tuple[str, str]] = ()) -> Callable[[str], str | None]:
    """A `find_package(name) -> folder or None` over the resolver chain (never a ROS lookup).

    Args:
        origin: the description file (its enclosing package and workspace are searched).
        package_paths: `--package-path` folders, searched first.
        package_map: explicit (package, folder) pairs from the config.
    """
    resolver = PackageResolver(PackageResolverConfig.from_environment(
        origin, tuple(package_paths), tuple(package_map)))

    @functools.lru_cache(maxsize=None)
    def find(name: str) -> str | None:
        found = resolver.find(name)
        return found.path if found else None

    return find
