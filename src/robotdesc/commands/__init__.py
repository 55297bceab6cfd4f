"""Every subcommand of `robotdesc`, one module each (`rules.py` holds `rules` and `rule`).

Each module listed in `COMMANDS`, with the subcommand names it adds, has
`register(subparsers, *, common, expansion)` that adds its parser(s) (with `common` and, when it
reads descriptions, `expansion` as parents) and sets `handler` to a function
`(argparse.Namespace) -> int` returning the exit code; the order here is the order of
`robotdesc --help`. The CLI imports only the chosen command's module (`modules_for`). Module
import must be cheap: import heavy libraries inside the handler. A command never imports `robotdesc.cli` (it sits above the commands).
"""

COMMANDS: tuple[tuple[str, tuple[str, ...]], ...] = (  # (module, the subcommands it adds)
    ("robotdesc.commands.lint", ("lint",)),
    ("robotdesc.commands.expand", ("expand",)),
    ("robotdesc.commands.rules", ("rules", "rule")),
    ("robotdesc.commands.inertia", ("inertia",)),
    ("robotdesc.commands.collision", ("collision",)),
    ("robotdesc.commands.sim", ("sim",)),
    ("robotdesc.commands.view", ("view",)),
    ("robotdesc.commands.report", ("report",)),
    ("robotdesc.commands.info", ("info",)),
    ("robotdesc.commands.srdf", ("srdf",)),
    ("robotdesc.commands.server", ("server",)),
)
COMMAND_MODULES: tuple[str, ...] = tuple(module for module, _ in COMMANDS)


def modules_for(argv: list[str]) -> tuple[str, ...]:
    """The command modules a command line needs: only the chosen command's when its first
    word names one (a warm `robotdesc expand` imports no other command), else all of them
    (`robotdesc --help`, a typo: argparse lists every command)."""
    first = next((word for word in argv if not word.startswith("-")), None)
    chosen = tuple(module for module, names in COMMANDS if first in names)
    return chosen or COMMAND_MODULES
