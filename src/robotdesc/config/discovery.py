"""The config of a file (the first found walking up: `config/files.py`), and loading one."""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import TYPE_CHECKING

from robotdesc.config.files import find_config_file, scanned_tree
from robotdesc.config.parse import parse_toml, read_text
from robotdesc.config.schema import Config
from robotdesc.config.validate import config_from_mapping
from robotdesc.errors import ConfigError
from robotdesc.source import Span
from robotdesc.trust import leaves_tree

if TYPE_CHECKING:
    from robotdesc.rules.registry import Rule


def discover_config(target: str, rules: Sequence[Rule] | None = None) -> Config:
    """The config for linting `target` (defaults when no config file is found).

    Args:
        target: the linted file.
        rules: the known rules (default: every registered rule).
    """
    found = find_config_file(target)
    return load_config(found, rules, scanned=True) if found else Config()


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
