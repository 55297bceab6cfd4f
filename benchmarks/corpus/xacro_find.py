"""The PyPI `xacro` command with `$(find pkg)` answered from given package folders, without ROS.

xacro 2.x resolves `$(find pkg)` (and `find()` in `${...}` expressions) through
`ament_index_python`, which needs a ROS install. This launcher replaces that one resolver with a
lookup in a table given on the command line, then runs xacro's own command-line entry point
unchanged, so a timing of this process is a timing of the xacro CLI.

Usage: python xacro_find.py --package NAME=DIR [--package NAME=DIR ...] -- XACRO_ARGS...
"""

from __future__ import annotations

import sys
from collections.abc import Callable


def split_argv(argv: list[str]) -> tuple[dict[str, str], list[str]]:
    """Split `--package NAME=DIR ... -- rest` into the package table and xacro's own arguments."""
    packages: dict[str, str] = {}
    index = 0
    while index < len(argv) and argv[index] != "--":
        if argv[index] != "--package" or index + 1 >= len(argv):
            raise SystemExit(f"xacro_find: expected --package NAME=DIR or --, got {argv[index]!r}")
        name, _, folder = argv[index + 1].partition("=")
        packages[name] = folder
        index += 2
    return packages, argv[index + 1:]


def make_resolver(packages: dict[str, str]) -> Callable[[str], str]:
    """A replacement for xacro's `_eval_find`: the package's folder, or xacro's usual failure."""

    def find(package: str) -> str:
        try:
            return packages[package]
        except KeyError:
            # the message ament_index_python gives for an unknown package
            message = f"package '{package}' not found, searching the given package folders"
            raise LookupError(message) from None

    return find


def install_resolver(find: Callable[[str], str]) -> None:
    """Point both uses of the resolver at `find`: `$(find ...)` and the `find` expression symbol."""
    from xacro import substitution_args

    substitution_args._eval_find = find
    substitution_args._eval_dict["find"] = find


def main() -> None:
    packages, xacro_argv = split_argv(sys.argv[1:])
    install_resolver(make_resolver(packages))
    import xacro

    sys.argv = ["xacro", *xacro_argv]
    xacro.main()


if __name__ == "__main__":
    main()
