"""Reads the files beside a description for the R1xx rules (`rules.package_files`): the
launch files, YAML, worlds, environment hooks, package.xml and CMakeLists.txt of the package
holding the description and of the packages its expansion resolved, and the controller
YAML files the description names. Bounded: a few levels deep, small files, no symlinks
followed out of a package, build and VCS folders skipped.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Iterable, Iterator, Sequence

from robotdesc.cache_dir import read_regular_file
from robotdesc.digest import FileStamp, entry_stamp
from robotdesc.expansion.packages import enclosing_package
from robotdesc.rules.package_files import (
    CMAKE,
    HOOK,
    LAUNCH_PY,
    LAUNCH_XML,
    MANIFEST,
    WORLD,
    YAML,
    Package,
    PackageFile,
    PackageFiles,
)
from robotdesc.trust import real_within

log = logging.getLogger(__name__)

#: Largest file read (bytes); bigger ones (generated worlds, bags) are skipped.
MAX_FILE_BYTES = 1_000_000
#: Most files read per package.
MAX_FILES = 400
#: How deep below a package's root files are looked for.
MAX_DEPTH = 4
_SKIPPED_DIRS = frozenset({"build", "install", "log", "meshes", "node_modules", "__pycache__",
                           "test", "tests", "doc", "docs"})


def read_package_files(source: str, package_dirs: Sequence[tuple[str, str]] = (),
                       named: Iterable[str] = ()) -> PackageFiles:
    """The packages of the description `source`.

    Args:
        source: the description (its enclosing package comes first).
        package_dirs: (name, folder) of the packages the expansion resolved.
        named: paths of YAML files the description names (read when they exist).
    """
    roots: list[tuple[str, str]] = []
    found = enclosing_package(os.path.dirname(os.path.abspath(source)))
    if found is not None:
        roots.append((found[0], str(found[1])))
    roots.extend(package_dirs)
    packages: list[Package] = []
    seen: set[str] = set()
    for name, folder in roots:
        real = os.path.realpath(folder)
        if real in seen or not os.path.isdir(real):
            continue
        seen.add(real)
        packages.append(Package(name, real, _package_files(real)))
    # the description names these: only files inside its packages are read (a
    # `<parameters>` naming ~/.config/... must not make the parent read it)
    named_files = tuple(f for f in (_read(os.path.realpath(p), YAML) for p in named
                                    if os.path.isabs(p) and p.endswith((".yaml", ".yml"))
                                    and real_within(p, tuple(seen))) if f is not None)
    return PackageFiles(tuple(packages), named_files)


def named_controller_files(xml: bytes) -> tuple[str, ...]:
    """The `<parameters>` paths of the ros2_control simulator plugins in a description."""
    if b"parameters" not in xml:
        return ()
    from robotdesc.xml_input import shared_root  # lxml: not on the path of a warm lint

    root = shared_root(xml)
    if root is None:
        return ()
    paths = []
    for plugin in root.iter("plugin"):
        if "ros2_control" not in (plugin.get("filename") or ""):
            continue
        for parameters in plugin.iter("parameters"):
            text = (parameters.text or "").strip()
            if text:
                paths.append(text)
    return tuple(paths)


def _kind(relative: str) -> str | None:
    """The kind of a file by its path inside the package, or None: not read."""
    name = os.path.basename(relative)
    parts = relative.split(os.sep)
    if relative == "package.xml":
        return MANIFEST
    if relative == "CMakeLists.txt":
        return CMAKE
    if name.endswith((".launch.py", "_launch.py")) or (parts[0] == "launch"
                                                       and name.endswith(".py")):
        return LAUNCH_PY
    if name.endswith((".launch", ".launch.xml")):
        return LAUNCH_XML
    if name.endswith((".yaml", ".yml")):
        return YAML
    if name.endswith((".world", ".sdf")) and "model" not in name:
        return WORLD
    if parts[0] in ("hooks", "env-hooks", "env_hooks") or name.endswith((".dsv.in", ".dsv",
                                                                            ".sh.in")):
        return HOOK
    return None


#: A folder listed or a file read, and its identity then (`digest.entry_stamp`).
_Seen = tuple[str, FileStamp | None]

#: Package folder (real path) -> its files as last read, and the state of every folder
#: listed and file read for them, each taken before it was listed or read: the variants of
#: a description and an editor's saves read the same packages again, and are given the
#: same files while none of those changed (a file added or removed changes its folder).
_READ: dict[str, tuple[tuple[PackageFile, ...], tuple[_Seen, ...]]] = {}
_READ_PACKAGES = 64


def _package_files(root: str) -> tuple[PackageFile, ...]:
    """The files of the package at `root` (a real path) read for the rules."""
    remembered = _READ.get(root)
    if remembered is not None and all(entry_stamp(path) == stamp
                                      for path, stamp in remembered[1]):
        return remembered[0]
    states: list[_Seen] = []
    files = tuple(found for path, kind in _walk(root, states)
                  if (found := _read(path, kind)) is not None)
    if len(_READ) >= _READ_PACKAGES:
        _READ.clear()
    _READ[root] = (files, tuple(states))
    return files


def _walk(root: str, states: list[_Seen]) -> Iterator[tuple[str, str]]:
    """The files of the kinds read, in path order; `states` gets the state of each folder
    before it is listed and of each file before it is read."""
    count = 0
    states.append((root, entry_stamp(root)))
    for folder, dirs, files in os.walk(root):
        relative_folder = os.path.relpath(folder, root)
        depth = 0 if relative_folder == "." else relative_folder.count(os.sep) + 1
        candidates = sorted(d for d in dirs if not d.startswith(".") and d not in _SKIPPED_DIRS
                            and depth < MAX_DEPTH)
        states.extend((path, entry_stamp(path)) for path in (os.path.join(folder, d)
                                                         for d in candidates))
        dirs[:] = [d for d in candidates if not os.path.islink(os.path.join(folder, d))
                   and not os.path.isfile(os.path.join(folder, d, "package.xml"))]
        for name in sorted(files):
            path = os.path.join(folder, name)
            kind = _kind(os.path.relpath(path, root))
            if kind is None or os.path.islink(path):
                continue
            count += 1
            if count > MAX_FILES:
                log.debug("%s: more than %d files, the rest not read", root, MAX_FILES)
                return
            states.append((path, entry_stamp(path)))
            yield path, kind


def _read(path: str, kind: str) -> PackageFile | None:
    """A regular file of at most `MAX_FILE_BYTES` (never a symlink, FIFO or device)."""
    data = read_regular_file(path, MAX_FILE_BYTES)
    if data is None:
        return None
    return PackageFile(path, kind, data.decode("utf-8", errors="replace"))


__all__ = ["named_controller_files", "read_package_files"]
