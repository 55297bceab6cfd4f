"""Resolve a `<mesh filename>` as written in a URDF to a file, or say why it cannot be.

Pure logic apart from file-system queries: the package lookup is passed in
(`find_package(name) -> root directory or None`), so the same code serves the ROS-free
package resolver and tests. Problems are values, not exceptions, so that a rule can report
each at its `<mesh>` line.
"""

from __future__ import annotations

import enum
import os
import stat
from collections.abc import Callable
from dataclasses import dataclass

PackageLookup = Callable[[str], "str | None"]


class ResolveProblemKind(str, enum.Enum):
    """Why a mesh reference does not lead to a usable file."""

    EMPTY = "empty"
    UNKNOWN_PACKAGE = "unknown-package"
    ESCAPES_ROOT = "escapes-root"
    ABSOLUTE_NOT_ALLOWED = "absolute-not-allowed"
    UNSUPPORTED_SCHEME = "unsupported-scheme"
    MISSING = "missing"
    CASE_MISMATCH = "case-mismatch"
    NOT_REGULAR_FILE = "not-regular-file"


@dataclass(frozen=True)
class ResolveProblem:
    """A reference that does not resolve.

    Attributes:
        kind: the reason.
        message: what is wrong, in a user's words.
        candidate: for CASE_MISMATCH, the existing file whose name differs only in case.
    """

    kind: ResolveProblemKind
    message: str
    candidate: str | None = None


@dataclass(frozen=True)
class MeshResolution:
    """The outcome of resolving one mesh reference.

    Attributes:
        filename: the reference as written.
        path: the resolved real path (symlinks followed) when usable, else None.
        problem: why it is not usable, else None.
        package: the package named by a `package://` reference.
        warnings: accepted but questionable spellings (e.g. `package:///`).
    """

    filename: str
    path: str | None = None
    problem: ResolveProblem | None = None
    package: str | None = None
    warnings: tuple[str, ...] = ()

    @property
    def ok(self) -> bool:
        return self.path is not None


def resolve_mesh(filename: str, *, base_dir: str, find_package: PackageLookup,
                 allow_absolute: bool = False, relative_root: str | None = None) -> MeshResolution:
    """Resolve a mesh filename from a URDF.

    Args:
        filename: the `filename` attribute as written.
        base_dir: directory of the URDF/xacro file that contains the `<mesh>`; relative
            paths are taken from here.
        find_package: returns a package's root directory, or None when unknown.
        allow_absolute: accept `file://` URIs and absolute paths (off by default: such a
            description works only on the author's machine).
        relative_root: a relative path must stay inside this directory (normally the root of
            the package that holds the URDF); None: no confinement.

    Returns:
        A resolution holding the real path or a problem.
    """
    text = filename.strip()
    if not text:
        return _problem(filename, ResolveProblemKind.EMPTY, "mesh filename is empty")
    scheme, sep, rest = text.partition("://")
    if sep and scheme == "package":
        return _resolve_package(filename, rest, find_package)
    if sep and scheme == "file":
        if not allow_absolute:
            return _problem(filename, ResolveProblemKind.ABSOLUTE_NOT_ALLOWED,
                            f"'{filename}' is a file:// URI; it works only on the machine "
                            "that wrote it (use package://)")
        return _finish(filename, "/" + rest.lstrip("/"), root=None)
    if sep:
        return _problem(filename, ResolveProblemKind.UNSUPPORTED_SCHEME,
                        f"'{filename}': the scheme '{scheme}://' is not supported "
                        "(use package://)")
    if os.path.isabs(text):
        if not allow_absolute:
            return _problem(filename, ResolveProblemKind.ABSOLUTE_NOT_ALLOWED,
                            f"'{filename}' is an absolute path; it works only on the machine "
                            "that wrote it (use package://)")
        return _finish(filename, text, root=None)
    return _finish(filename, os.path.join(base_dir, text), root=relative_root)


def local_path(filename: str) -> str | None:
    """The path on this machine a `file://` URI or an absolute path names (None for any other
    reference): what a consumer opens, whether or not the config allows such paths."""
    text = filename.strip()
    scheme, sep, rest = text.partition("://")
    if sep:
        return "/" + rest.lstrip("/") if scheme == "file" else None
    return text if text and os.path.isabs(text) else None


def _resolve_package(filename: str, rest: str, find_package: PackageLookup) -> MeshResolution:
    warnings: tuple[str, ...] = ()
    if rest.startswith("/"):
        warnings = ((f"'{filename}' has three slashes after 'package:'; write "
                     f"'package://{rest.lstrip('/')}'"),)
        rest = rest.lstrip("/")
    package, _, relative = rest.partition("/")
    if not package or not relative:
        return _problem(filename, ResolveProblemKind.EMPTY,
                        f"'{filename}' names no package or no file inside it", warnings)
    root = find_package(package)
    if root is None:
        return _problem(filename, ResolveProblemKind.UNKNOWN_PACKAGE,
                        f"unknown package '{package}' in '{filename}'", warnings,
                        package=package)
    found = _finish(filename, os.path.join(root, relative), root=root)
    return MeshResolution(filename, found.path, found.problem, package, warnings)


def _finish(filename: str, candidate: str, root: str | None) -> MeshResolution:
    """Check that `candidate` stays under `root` (after symlinks) and is a regular file."""
    real = os.path.realpath(candidate)
    if root is not None:
        real_root = os.path.realpath(root)
        if os.path.commonpath([real_root, real]) != real_root:
            return _problem(filename, ResolveProblemKind.ESCAPES_ROOT,
                            f"'{filename}' leads to {real}, outside its package root "
                            f"{real_root}")
    try:
        mode = os.stat(real).st_mode
    except FileNotFoundError:
        return _missing(filename, candidate, real, root)
    except OSError as error:
        return _problem(filename, ResolveProblemKind.MISSING,
                        f"'{filename}' cannot be read: {error.strerror}")
    if not stat.S_ISREG(mode):
        what = _kind_of(mode)
        return _problem(filename, ResolveProblemKind.NOT_REGULAR_FILE,
                        f"'{filename}' is {what}, not a regular file")
    return MeshResolution(filename, path=real)


def _missing(filename: str, candidate: str, real: str, root: str | None) -> MeshResolution:
    match = find_case_insensitive(real, os.path.realpath(root) if root else None)
    if match is not None:
        return _problem(filename, ResolveProblemKind.CASE_MISMATCH,
                        f"'{filename}' does not exist, but '{os.path.basename(match)}' does: "
                        "the names differ only in case (this works on Windows and macOS, "
                        "not on Linux)", candidate=match)
    return _problem(filename, ResolveProblemKind.MISSING, f"'{filename}' not found ({real})")


def find_case_insensitive(path: str, root: str | None = None) -> str | None:
    """An existing path that equals `path` ignoring case, component by component.

    Args:
        path: an absolute, normalised path that does not exist.
        root: start matching below this existing directory (None: from the deepest existing
            ancestor of `path`).

    Returns:
        The unique existing match, or None when there is none or it is ambiguous.
    """
    start = root or path
    while not os.path.isdir(start):
        parent = os.path.dirname(start)
        if parent == start:
            return None
        start = parent
    relative = os.path.relpath(path, start)
    if relative.startswith(".."):
        return None
    current = start
    for part in relative.split(os.sep):
        try:
            names = os.listdir(current)
        except OSError:
            return None
        matches = [part] if part in names else [n for n in names
                                                 if n.casefold() == part.casefold()]
        if len(matches) != 1:
            return None
        current = os.path.join(current, matches[0])
    return current if current != path and os.path.exists(current) else None


def _kind_of(mode: int) -> str:
    if stat.S_ISDIR(mode):
        return "a directory"
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe)"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a regular file"


def _problem(filename: str, kind: ResolveProblemKind, message: str,
             warnings: tuple[str, ...] = (), package: str | None = None,
             candidate: str | None = None) -> MeshResolution:
    return MeshResolution(filename, problem=ResolveProblem(kind, message, candidate),
                          package=package, warnings=warnings)
