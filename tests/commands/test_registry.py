"""Every subcommand comes from its module in `COMMAND_MODULES`, in the order of --help."""

from __future__ import annotations

import argparse
import importlib

import pytest

from robotdesc.cli import build_parser, main
from robotdesc.commands import COMMAND_HELP, COMMAND_MODULES, COMMANDS, modules_for


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


def test_the_declared_names_are_the_registered_ones() -> None:
    declared = [name for _, names in COMMANDS for name in names]
    assert declared == _subcommands(build_parser())


def test_a_command_line_imports_only_its_command() -> None:
    assert modules_for(["expand", "robot.urdf.xacro", "--no-cache"]) == (
        "robotdesc.commands.expand",)
    assert modules_for(["rule", "J101"]) == ("robotdesc.commands.rules",)
    assert _subcommands(build_parser(["expand", "x.xacro"])) == ["expand"]
    for nothing in ([], ["--help"], ["--version"], ["lnt", "x.urdf"]):
        assert modules_for(nothing) == ()


def test_without_a_command_every_command_is_listed_with_its_registered_help() -> None:
    def helps(parser: argparse.ArgumentParser) -> dict[str, str | None]:
        action = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
        return {choice.dest: choice.help for choice in action._choices_actions}

    assert helps(build_parser(["--help"])) == helps(build_parser()) == COMMAND_HELP


def test_a_typo_in_the_command_still_lists_every_command(
        capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["lnt", "x.urdf"]) == 2
    err = capsys.readouterr().err
    assert "invalid choice: 'lnt'" in err and "'lint'" in err and "'srdf'" in err
