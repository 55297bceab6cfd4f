"""Command-line paths -> the description files to lint."""

from __future__ import annotations

import os
from typing import Iterable

from robotdesc.errors import InputError
from robotdesc.source import Span

#: File names a directory walk picks up. A bare `.xacro` is usually a macro library that
#: `<xacro:include>`s pull in, not a robot, so it is linted only when named explicitly.
DESCRIPTION_SUFFIXES = (".urdf", ".urdf.xacro")
_SKIPPED_DIRS = {"build", "install", "log", "node_modules", "__pycache__"}


def collect_targets(paths: Iterable[str]) -> list[str]:
    """Expand directories into the descriptions under them; keep files as given.

    Raises:
        InputError: a path does not exist, or a directory holds no description.
    """
    targets: list[str] = []
    for path in paths:
        if os.path.isdir(path):
            found = sorted(_walk(path))
            if not found:
                raise InputError("no *.urdf or *.urdf.xacro file under this directory",
                                 Span(path))
            targets.extend(found)
        elif os.path.exists(path):
            targets.append(path)
        else:
            raise InputError("no such file or directory", Span(path))
    return list(dict.fromkeys(targets))


def _walk(root: str) -> Iterable[str]:
    for directory, subdirs, files in os.walk(root):
        subdirs[:] = sorted(d for d in subdirs
                            if not d.startswith(".") and d not in _SKIPPED_DIRS)
        for name in files:
            if name.endswith(DESCRIPTION_SUFFIXES):
                yield os.path.join(directory, name)
