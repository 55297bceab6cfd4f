"""Which config file applies to a file (the first found walking up), and loading one."""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import TYPE_CHECKING

from robotdesc.config.parse import parse_toml, read_text
from robotdesc.config.schema import Config
from robotdesc.config.validate import config_from_mapping
from robotdesc.errors import ConfigError
from robotdesc.source import Span
from robotdesc.trust import leaves_tree

if TYPE_CHECKING:
    from robotdesc.rules.registry import Rule

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
            if os.path.isfile(candidate) and _configures_robotdesc(candidate):
                return candidate
        parent = os.path.dirname(directory)
        if parent == directory or any(os.path.exists(os.path.join(directory, marker))
                                      for marker in VCS_MARKERS):
            return None
        directory = parent


def discover_config(target: str, rules: Sequence[Rule] | None = None) -> Config:
    """The config for linting `target` (defaults when no config file is found).

    Args:
        target: the linted file.
        rules: the known rules (default: every registered rule).
    """
    found = find_config_file(target)
    return load_config(found, rules, scanned=True) if found else Config()


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


def load_config(path: str, rules: Sequence[Rule] | None = None, *,
                scanned: bool = False) -> Config:
    """Read and validate one config file (robotdesc.toml or pyproject.toml).

    Args:
        scanned: the config was found in the scanned tree (not named by the user with
            `--config`): it may only name folders inside its repository, and a config file
            that is a symlink out of it is refused.

    Raises:
        ConfigError: unreadable TOML, unknown keys, bad values, a path outside the tree;
            the message names the file.
    """
    path = os.path.abspath(path)
    tree = scanned_tree(path) if scanned else None
    if tree is not None and leaves_tree(path, tree):
        raise ConfigError("config file is a symlink out of the repository that holds it; "
                          "not read", Span(path))
    text = read_text(path)
    document = parse_toml(text, path)
    if os.path.basename(path) == "pyproject.toml":
        table = document.get("tool", {}).get("robotdesc", {})
        prefix = "tool.robotdesc."
    else:
        table = document
        prefix = ""
    return config_from_mapping(table, path, text=text, prefix=prefix, rules=rules, tree=tree)


def _configures_robotdesc(path: str) -> bool:
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
