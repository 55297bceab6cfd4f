"""The `robotdesc` command: build the parser, set up logging, run the chosen command and turn
what escapes it into the exit code. The commands themselves live in `robotdesc/commands/`.

Exit codes: 0 no finding at or above --fail-on, 1 findings, 2 an input could not be checked
(or the command line is wrong), 3 internal error (a bug), 130 interrupted.
Start-up is one interpreter and little more: only the chosen command's module is imported
(`robotdesc --version` and `--help` import none), heavy modules are imported inside the
commands, and the failure renderer only when an input fails (tests/test_startup.py).
"""

from __future__ import annotations

import importlib
import logging
import os
import sys
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

from robotdesc._version import __version__
from robotdesc.commands import COMMAND_HELP, COMMAND_MODULES, modules_for
from robotdesc.commands.exit_codes import EXIT_INPUT, EXIT_INTERNAL, EXIT_INTERRUPTED, EXIT_OK

if TYPE_CHECKING:
    import argparse

    from robotdesc.commands.lint_replay import Recording, ReplayRecord

BUG_REPORT_URL = "https://github.com/robotdesc/robotdesc/issues"


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code (the console script exits with it)."""
    words = list(sys.argv[1:] if argv is None else argv)
    if _expands_first(words):
        from robotdesc.expansion.launch import start_early  # subprocess: only then

        start_early()
    try:
        return _dispatch(words)
    finally:
        launch = sys.modules.get("robotdesc.expansion.launch")
        if launch is not None:  # a worker started early that no expansion took: ended now
            launch.drop_early()


def _expands_first(words: list[str]) -> bool:
    """Whether the command line is a `lint` or `expand` of a xacro file that reads no cache
    (--no-cache: not even the replay of a lint answers it), so that its first work is to
    start the xacro worker: started at once, its interpreter start and imports (about 50 ms)
    run beside this process's own (`expansion.launch.start_early`). A guess from the words
    only: a wrong one costs an idle process, killed when the command ends."""
    return words[:1] in (["lint"], ["expand"]) and "--no-cache" in words \
        and not any(word.startswith("--scheduler") for word in words) \
        and any(".xacro" in word for word in words[1:] if not word.startswith("-"))


def _dispatch(words: list[str]) -> int:
    """The command line's run: an unchanged lint's replay, or `_main`."""
    if words[:1] != ["lint"]:
        return _main(words, None)
    from robotdesc.commands import lint_replay  # only for a lint (--version must not pay)

    try:
        replayed = lint_replay.replay(words)  # an unchanged lint: what the last identical run said
    except KeyboardInterrupt:
        sys.stderr.write("robotdesc: interrupted\n")
        return EXIT_INTERRUPTED
    except BrokenPipeError:  # `robotdesc lint FILE | head`
        _silence_stdout()
        return EXIT_OK
    if replayed is not None:
        return replayed
    return _main(words, lint_replay.Recording())


def _main(words: list[str], recording: Recording | None) -> int:
    """Parse and run the command line; a lint under `recording`, stored for its replay when
    the whole-result cache answered it (`commands/lint_replay.py`)."""
    parser = build_parser(words)
    if not words:  # bare `robotdesc`: what it can do
        parser.print_help(sys.stdout)
        return EXIT_OK
    try:
        ns = _parse(parser, words)
    except SystemExit as exc:  # --help, --version (0) and usage errors (2)
        return exc.code if isinstance(exc.code, int) else EXIT_INPUT
    verbose: int = getattr(ns, "verbose", 0)
    if recording is None:
        return _logged_run(ns, verbose)
    with recording:
        code = _logged_run(ns, verbose)
    record: ReplayRecord | None = getattr(ns, "replay", None)
    if record is not None:
        recording.store(words, record, code)
    return code


def _logged_run(ns: argparse.Namespace, verbose: int) -> int:
    """`_run` with robotdesc's messages logged to stderr."""
    restore = _configure_logging(verbose)
    try:
        return _run(ns, verbose)
    finally:
        restore()  # leave the "robotdesc" logger as it was (main() may run in-process)


def _parse(parser: argparse.ArgumentParser, words: list[str]) -> argparse.Namespace:
    """Parse the command line, letting files and `name:=value` arguments come after options
    too (`robotdesc lint FILE --no-cache name:=value`, as xacro and roslaunch users write)."""
    ns, extra = parser.parse_known_args(words)
    inputs = getattr(ns, "inputs", None)
    if extra and isinstance(inputs, list) and not any(w.startswith("-") for w in extra):
        inputs.extend(extra)
        return ns
    if extra:
        parser.parse_args(words)  # argparse's own usage error for what it does not know
    return ns


def _run(ns: argparse.Namespace, verbose: int) -> int:
    """Run the chosen command, turning every failure into its exit code."""
    try:
        code: int = ns.handler(ns)
        return code
    except KeyboardInterrupt:
        sys.stderr.write("robotdesc: interrupted\n")
        return EXIT_INTERRUPTED
    except BrokenPipeError:  # e.g. `robotdesc rules | head`
        _silence_stdout()
        return EXIT_OK
    except Exception as exc:  # noqa: BLE001 (an input error, else a bug: say so; -v: traceback)
        if _is_input_error(exc):  # path:line:col: error: message, the source, the call chain
            sys.stderr.write(_render_input_error(exc))
            return EXIT_INPUT
        detail = str(exc)
        detail = detail if len(detail) <= 500 else detail[:500] + f"... ({len(detail)} characters)"
        sys.stderr.write(f"robotdesc: internal error: {type(exc).__name__}: {detail}\n"
                         f"This is a bug in robotdesc, not a problem with your files; please "
                         f"report it at {BUG_REPORT_URL} "
                         "with the command you ran"
                         + (".\n" if verbose else " (run with --verbose for the traceback).\n"))
        if verbose:
            import traceback

            traceback.print_exc(file=sys.stderr)
        return EXIT_INTERNAL


def _is_input_error(exc: Exception) -> bool:
    """Whether `exc` is an `InputError` (exit 2). The error classes, the failure renderer and
    `dataclasses` under them are imported only when a command fails: `robotdesc --version`
    and `--help` must not pay for them."""
    from robotdesc.errors import InputError

    return isinstance(exc, InputError)


def _render_input_error(exc: Exception) -> str:
    """An input error as every command prints it (see `_is_input_error` for the imports)."""
    from robotdesc.errors import InputError
    from robotdesc.linting.result import LintFailure
    from robotdesc.report.text import render_failure

    assert isinstance(exc, InputError)
    return render_failure(LintFailure("robotdesc", exc))


def build_parser(argv: Sequence[str] | None = None) -> argparse.ArgumentParser:
    """The argument parser (cheap: no heavy imports). Without a command line: every subcommand,
    complete. Given one: only the subcommand it names (`modules_for`); when it names none
    (`--version`, `--help`, a typo), every subcommand as a name and its help only, without
    importing a command module."""
    import argparse  # here, not at the top: the replay of an unchanged lint parses nothing

    parser = argparse.ArgumentParser(
        prog="robotdesc",
        description="Expand xacro without ROS, and lint robot descriptions (URDF/xacro).",
        epilog="Exit codes: 0 clean, 1 findings, 2 input could not be checked, 3 internal error.")
    parser.add_argument("--version", action="version", version=f"robotdesc {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)

    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("-v", "--verbose", action="count", default=0,
                        help="log package resolution and progress to stderr (twice: debug)")
    common.add_argument("-q", "--quiet", action="store_true",
                        help="no progress on stderr (shown for long runs: a bar on a "
                             "terminal, a line every few seconds otherwise)")
    expansion = argparse.ArgumentParser(add_help=False)
    expansion.add_argument("--package-path", action="append", default=[], metavar="DIR",
                           help="a folder holding ROS packages (or one package); repeatable; "
                                "searched first")
    expansion.add_argument("--trusted", action="store_true",
                           help="lift the sandbox limits (only for your own files)")
    expansion.add_argument("--no-cache", action="store_true",
                           help="expand again even when no input changed")
    expansion.add_argument("--config", metavar="FILE",
                           help="use this robotdesc.toml / pyproject.toml instead of searching")
    expansion.add_argument("--timeout", type=float, default=60.0, metavar="SECONDS",
                           help="wall-clock limit of one xacro expansion (default: 60)")
    expansion.add_argument("--env", action="append", default=[], metavar="NAME",
                           help="let $(env NAME)/$(optenv NAME) see this variable in safe mode; "
                                "repeatable")

    modules = COMMAND_MODULES if argv is None else modules_for(list(argv))
    for module in modules:  # each: register(commands, common=..., expansion=...)
        importlib.import_module(module).register(commands, common=common, expansion=expansion)
    if not modules:  # listed for --help and a typo's "invalid choice"; never run
        for name, summary in COMMAND_HELP.items():
            commands.add_parser(name, help=summary)
    return parser


def _configure_logging(verbose: int) -> Callable[[], None]:
    """Log robotdesc's messages to stderr; returns a function that undoes it."""
    level = logging.WARNING if not verbose else logging.INFO if verbose == 1 else logging.DEBUG
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("robotdesc: %(message)s"))
    root = logging.getLogger("robotdesc")
    saved = (root.handlers[:], root.level, root.propagate)
    root.handlers[:] = [handler]
    root.setLevel(level)
    root.propagate = False

    def restore() -> None:
        root.handlers[:], root.level, root.propagate = saved[0], saved[1], saved[2]

    return restore


def _silence_stdout() -> None:
    """Point stdout at /dev/null (its reader is gone: nothing more to say)."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
