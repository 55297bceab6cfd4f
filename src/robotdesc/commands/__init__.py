"""Every subcommand of `robotdesc`, one module each (`rules.py` holds `rules` and `rule`).

Each module listed in `COMMANDS`, with the subcommand names it adds, has
`register(subparsers, *, common, expansion)` that adds its parser(s) (with `common` and, when it
reads descriptions, `expansion` as parents) and sets `handler` to a function
`(argparse.Namespace) -> int` returning the exit code; the order here is the order of
`robotdesc --help`. The CLI imports only the chosen command's module (`modules_for`); a command
line that names none (`--version`, `--help`, a typo) imports no command module at all and lists
the commands from `COMMAND_HELP` (a test keeps it equal to what the modules register). Module
import must be cheap: import heavy libraries inside the handler. A command never imports
`robotdesc.cli` (it sits above the commands).
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

#: Each subcommand's one-line help in `robotdesc --help` (the module registers the same).
COMMAND_HELP: dict[str, str] = {
    "lint": "lint descriptions",
    "expand": "expand a xacro file to URDF",
    "rules": "list the rules",
    "rule": "show one rule's documentation",
    "inertia": "compare inertials with the geometry",
    "collision": "make collision meshes, measured",
    "sim": "physics settle test and real-time factor",
    "view": "write a 3D view as one HTML page",
    "report": "write an HTML report",
    "info": "kinematic and mass summary (Pinocchio)",
    "srdf": "self-collision matrix as SRDF (Pinocchio)",
    "server": "run the language server (LSP, stdio)",
}


def modules_for(argv: list[str]) -> tuple[str, ...]:
    """The command modules a command line needs: only the chosen command's when its first
    word names one (a warm `robotdesc expand` imports no other command), else none
    (`robotdesc --version`, `--help`, a typo: the commands are listed from `COMMAND_HELP`)."""
    first = next((word for word in argv if not word.startswith("-")), None)
    return tuple(module for module, names in COMMANDS if first in names)
