"""The one writer of every output a command produces (reports, baselines, URDF, pages, SRDF,
patches, collision files).

- It refuses to write over a file the run read (`RunInputs`: the input, the files the
  expansion included, package.xml, the config, the meshes), compared by real path and by
  inode, so a symlink or hard link to an input is refused too.
- A symlink or a device, FIFO or socket (`-o /dev/null`, `-o /dev/stdout`) is written as a
  stream to what it points at and stays what it is.
- A regular file is replaced atomically (`robotdesc.atomic`): the umask decides a new file's
  mode, a replaced file keeps its own; the temporary is removed on SIGTERM/SIGINT and a
  stale one (SIGKILL) is removed by the next write.
- A folder that is a file, a read-only folder or a target that is a folder is an
  `OutputError` (exit 2) naming the path.
"""

from __future__ import annotations

import errno
import os
import stat
from collections.abc import Iterable
from dataclasses import dataclass

from robotdesc.atomic import Data, write_atomically
from robotdesc.errors import OutputError
from robotdesc.trust import RealPaths


@dataclass(frozen=True)
class RunInput:
    """A file the run read.

    Attributes:
        path: its real path (symlinks resolved).
        what: what it is, in a user's words ("the description being checked").
    """

    path: str
    what: str


@dataclass(frozen=True)
class RunInputs:
    """The files a run read, which no output of that run may replace."""

    items: tuple[RunInput, ...] = ()

    def adding(self, paths: Iterable[str | os.PathLike[str] | None], what: str) -> RunInputs:
        """These inputs plus `paths` (None entries skipped), all described as `what`."""
        known = {item.path for item in self.items}
        extra = []
        real_path = RealPaths()  # a description's files share a few folders
        for path in paths:
            if not path:
                continue
            real = real_path(os.path.abspath(os.fspath(path)))
            if real not in known:
                known.add(real)
                extra.append(RunInput(real, what))
        return RunInputs(self.items + tuple(extra))

    def __add__(self, other: RunInputs) -> RunInputs:
        known = {item.path for item in self.items}
        return RunInputs(self.items + tuple(i for i in other.items if i.path not in known))

    def match(self, path: str | os.PathLike[str]) -> RunInput | None:
        """The input that `path` would overwrite (same real path, or the same inode), or
        None."""
        real = os.path.realpath(os.fspath(path))
        for item in self.items:
            if item.path == real:
                return item
        try:
            target = os.stat(real)
        except OSError:
            return None
        identity = (target.st_dev, target.st_ino)
        for item in self.items:
            try:
                info = os.stat(item.path)
            except OSError:
                continue
            if (info.st_dev, info.st_ino) == identity:
                return item
        return None


NO_INPUTS = RunInputs()


def check_output(path: str, inputs: RunInputs = NO_INPUTS, *,
                 within: str | None = None) -> None:
    """Refuse early (before the work) an output that would replace an input of the run, or
    (with `within`) leave that folder.

    Raises:
        OutputError: `path` is (or leads to) an input, or lies outside `within`.
    """
    if within is not None:
        _check_within(path, within)
    found = inputs.match(path)
    if found is not None:
        where = "" if os.path.abspath(path) == found.path else f": {found.path}"
        raise OutputError(path, f"it is an input of this run ({found.what}{where})",
                          message=f"refusing to write {path}: it is an input of this run "
                                  f"({found.what}{where}); choose another output")


def write_output(path: str, data: Data, inputs: RunInputs = NO_INPUTS, *,
                 within: str | None = None) -> None:
    """Write a command's output (see the module docstring).

    Args:
        path: where, as the user gave it.
        data: the bytes, or an iterable of chunks.
        inputs: the files the run read; none of them is written.
        within: a folder the output must stay in (collision outputs): then a symlink, a
            special file or a path leaving the folder is refused instead of followed.

    Raises:
        OutputError: the path is an input, a folder, outside `within`, or its folder
            cannot be written (exit 2).
    """
    check_output(path, inputs, within=within)
    try:
        link = os.path.islink(path)
        info = os.stat(path)
    except FileNotFoundError:
        info = None
    except OSError as error:
        raise _explain(path, error) from None
    if info is not None and stat.S_ISDIR(info.st_mode):
        raise OutputError(path, "it is a folder")
    if link and info is None:
        raise OutputError(path, "it is a symlink to a missing file")
    try:
        if link or (info is not None and not stat.S_ISREG(info.st_mode)):
            _stream(path, data, truncate=info is not None and stat.S_ISREG(info.st_mode))
        else:
            write_atomically(path, data, durable=True)
    except OSError as error:
        raise _explain(path, error) from None


def check_output_dir(path: str) -> None:
    """Check, creating nothing, that the output folder `path` can be made and written (so a
    long run does not fail at its end).

    Raises:
        OutputError: it (or a folder above it) is a file, or it is read-only.
    """
    folder = os.path.abspath(path)
    current = folder
    while not os.path.lexists(current):
        parent = os.path.dirname(current)
        if parent == current:
            return
        current = parent
    if not os.path.isdir(current):
        raise OutputError(path, "it is a file, not a folder" if current == folder
                          else f"{current} is a file, not a folder")
    if not os.access(current, os.W_OK | os.X_OK):
        raise OutputError(path, "the folder is read-only (no permission to write in it)"
                          if current == folder else f"cannot create it: {current} is read-only")


def prepare_output_dir(path: str) -> str:
    """Create the output folder `path` when missing; returns its absolute path.

    Raises:
        OutputError: it (or a folder above it) is a file, or it cannot be written.
    """
    folder = os.path.abspath(path)
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as error:
        raise _explain(path, error, folder=folder) from None
    if not os.path.isdir(folder):
        raise OutputError(path, "it is a file, not a folder")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise OutputError(path, "the folder is read-only (no permission to write in it)")
    return folder


def _check_within(path: str, folder: str) -> None:
    root = os.path.realpath(folder)
    parent = os.path.realpath(os.path.dirname(os.path.abspath(path)))
    if os.path.commonpath([root, parent]) != root:
        raise OutputError(path, f"it would be written outside the output folder {folder} "
                                f"(through {parent})")
    try:
        info = os.lstat(path)
    except FileNotFoundError:
        return
    except OSError as error:
        raise _explain(path, error) from None
    if not stat.S_ISREG(info.st_mode):
        raise OutputError(path, "it is a symlink or a special file inside the output folder; "
                                "robotdesc writes only regular files there")


def _stream(path: str, data: Data, truncate: bool) -> None:
    """Write through a symlink or into a device/FIFO without replacing it."""
    flags = os.O_WRONLY | os.O_CLOEXEC | (os.O_TRUNC if truncate else 0)
    handle = os.open(path, flags)
    with os.fdopen(handle, "wb") as stream:
        for chunk in [data] if isinstance(data, (bytes, bytearray, memoryview)) else data:
            stream.write(chunk)


def _explain(path: str, error: OSError, folder: str | None = None) -> OutputError:
    """An `OutputError` that says which folder is wrong and why."""
    code = error.errno
    if code in (errno.ENOTDIR, errno.EEXIST):
        blocker = _file_in_the_way(folder or os.path.dirname(os.path.abspath(path)))
        if blocker is not None:
            return OutputError(path, f"{blocker} is a file, not a folder")
    if code == errno.EISDIR:
        return OutputError(path, "it is a folder")
    if code in (errno.EACCES, errno.EPERM, errno.EROFS):
        where = folder or os.path.dirname(os.path.abspath(path))
        reason = (error.strerror or str(error)).lower()
        return OutputError(path, f"{reason} (is the folder {where} read-only?)")
    return OutputError(path, (error.strerror or str(error)).lower())


def _file_in_the_way(folder: str) -> str | None:
    """The nearest existing ancestor of `folder` (itself included) that is not a folder."""
    current = folder
    while True:
        if os.path.lexists(current):
            return None if os.path.isdir(current) else current
        parent = os.path.dirname(current)
        if parent == current:
            return None
        current = parent
