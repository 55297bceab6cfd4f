"""The one description a command works on: its file, `name:=value` arguments, config and
expansion options, read from the command line the same way by every one-file command.

The expansion package (lxml underneath) is imported when a command runs, so that
`robotdesc --help` stays light."""

from __future__ import annotations

import argparse
import dataclasses
import os
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from robotdesc.commands.exit_codes import EXIT_FINDINGS as EXIT_FINDINGS  # re-exported
from robotdesc.commands.exit_codes import EXIT_INPUT as EXIT_INPUT
from robotdesc.commands.exit_codes import EXIT_INTERNAL as EXIT_INTERNAL
from robotdesc.commands.exit_codes import EXIT_INTERRUPTED as EXIT_INTERRUPTED
from robotdesc.commands.exit_codes import EXIT_OK as EXIT_OK
from robotdesc.config import discover_config, load_config
from robotdesc.errors import UsageError
from robotdesc.expansion import ExpandOptions
from robotdesc.linting.targets import LintTarget

if TYPE_CHECKING:
    from robotdesc.config import Config
    from robotdesc.expansion import ExpandOptions  # noqa: TC004



def split_inputs(inputs: Sequence[str]) -> tuple[list[str], dict[str, str]]:
    """Separate paths from `name:=value` xacro arguments."""
    paths, args = [], {}
    for item in inputs:
        name, sep, value = item.partition(":=")
        if sep and name and not os.path.exists(item):
            if not name.replace("_", "").replace("-", "").isalnum():
                raise UsageError(f"bad xacro argument '{item}' (expected name:=value)")
            args[name] = value
        elif "=" in item and not os.path.exists(item) \
                and item.partition("=")[0].replace("_", "").replace("-", "").isalnum():
            name, _, value = item.partition("=")  # a xacro argument without its colon
            raise UsageError(f"'{item}' is neither a file nor a xacro argument; xacro "
                             f"arguments take a colon: {name}:={value}")
        else:
            paths.append(item)
    if not paths:
        raise UsageError("no file given")
    return paths, args


@dataclass(frozen=True)
class SingleInput:
    """The one description a command works on, with what its config says about it.

    Attributes:
        source: the file's path as given.
        cli_args: the `name:=value` xacro arguments from the command line.
        config: the config given with --config, or found from the file.
        options: the expansion options (command line and the config's packages).
    """

    source: str
    cli_args: dict[str, str]
    config: "Config"
    options: "ExpandOptions"

    @property
    def args(self) -> dict[str, str]:
        """The xacro arguments: the config's, overridden by the command line's."""
        return {**dict(self.config.args), **self.cli_args}


def single_input(ns: argparse.Namespace, verb: str) -> SingleInput:
    """Read `ns.inputs` as one file plus xacro arguments, and load its config.

    Raises:
        UsageError: not exactly one file, a bad argument or a bad option.
    """
    paths, args = split_inputs(ns.inputs)
    if len(paths) != 1:
        raise UsageError(f"{verb} takes one file, got {len(paths)}: {' '.join(paths)}")
    source = paths[0]
    config = load_config(ns.config) if ns.config else discover_config(source)
    if os.path.isfile(source) and args:  # an undeclared one: a usage error before any work
        from robotdesc.linting.arguments import check_cli_arguments  # lxml: not for --help

        check_cli_arguments([LintTarget(os.path.abspath(source), config)], args)
    options = expand_options(ns, config.packages)  # the config's default args may go unused
    options = dataclasses.replace(options, unchecked_args=tuple(
        name for name, _ in config.args if name not in args))
    return SingleInput(source, args, config, options)


def expand_options(ns: argparse.Namespace,
                   package_map: Sequence[tuple[str, str]] = ()) -> "ExpandOptions":
    """The expansion options of the command line (and the config's package map)."""
    if ns.timeout <= 0:
            raise UsageError("--timeout must be positive")
    return ExpandOptions(package_paths=tuple(os.path.abspath(p) for p in ns.package_path),
                         package_map=tuple(package_map), trusted=ns.trusted,
                         use_cache=not ns.no_cache, timeout_s=ns.timeout,
                         env_allowlist=tuple(ns.env))
