"""Every subcommand comes from its module in `COMMAND_MODULES`, in the order of --help."""

from __future__ import annotations

import argparse
import importlib

from robotdesc.cli import build_parser
from robotdesc.commands import COMMAND_MODULES


def _subcommands(parser: argparse.ArgumentParser) -> list[str]:
    action = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return list(action.choices)


def test_each_module_registers_its_commands_in_order() -> None:
    names = _subcommands(build_parser())
    assert names[:4] == ["lint", "expand", "rules", "rule"]
    common = argparse.ArgumentParser(add_help=False)
    registered = []
    for module in COMMAND_MODULES:
        parser = argparse.ArgumentParser()
        sub = parser.add_subparsers(dest="command")
        importlib.import_module(module).register(sub, common=common, expansion=common)
        found = _subcommands(parser)
        assert found, f"{module} registers no subcommand"
        for name in found:
            assert callable(sub.choices[name].get_default("handler")), (module, name)
        registered += found
    assert registered == names
