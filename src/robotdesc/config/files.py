"""Which config file applies to a file: the first found walking up from it.

Cheap to import (os, and the TOML reader only for a pyproject.toml that names robotdesc):
the replay of an unchanged lint (`commands/lint_replay.py`) asks it before anything else.
"""

from __future__ import annotations

import os

from robotdesc.config.parse import parse_toml

#: The config files of a directory, in precedence order.
CONFIG_FILES = ("robotdesc.toml", "pyproject.toml")
#: A directory holding one of these is a repository root: the walk up stops after it.
VCS_MARKERS = (".git", ".hg", ".svn")


def find_config_file(start: str) -> str | None:
    """The first config file that configures robotdesc, walking up from `start`.

    Args:
        start: a file or directory; the walk begins at its directory.
    """
    directory = os.path.abspath(start)
    if not os.path.isdir(directory):
        directory = os.path.dirname(directory)
    while True:
        for name in CONFIG_FILES:
            candidate = os.path.join(directory, name)
            if os.path.isfile(candidate) and configures_robotdesc(candidate):
                return candidate
        parent = os.path.dirname(directory)
        if parent == directory or any(os.path.exists(os.path.join(directory, marker))
                                      for marker in VCS_MARKERS):
            return None
        directory = parent


def scanned_tree(config_path: str) -> str:
    """The tree a discovered config belongs to: the nearest folder at or above it holding a
    VCS marker (the repository), else the config's own folder."""
    folder = os.path.dirname(os.path.abspath(config_path))
    here = folder
    while True:
        if any(os.path.exists(os.path.join(here, marker)) for marker in VCS_MARKERS):
            return here
        parent = os.path.dirname(here)
        if parent == here:
            return folder
        here = parent


def configures_robotdesc(path: str) -> bool:
    """robotdesc.toml always does; pyproject.toml only with a [tool.robotdesc] table."""
    if os.path.basename(path) != "pyproject.toml":
        return True
    try:
        with open(path, encoding="utf-8", errors="replace") as handle:
            text = handle.read()
    except OSError:
        return False
    if "robotdesc" not in text:
        return False
    return "robotdesc" in parse_toml(text, path).get("tool", {})
