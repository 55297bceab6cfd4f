"""Every subcommand of `robotdesc`, one module each (`rules.py` holds `rules` and `rule`).

Each module listed here has `register(subparsers, *, common, expansion)` that adds its
parser(s) (with `common` and, when it reads descriptions, `expansion` as parents) and sets
`handler` to a function `(argparse.Namespace) -> int` returning the exit code; the order here
is the order of `robotdesc --help`. Module import must be cheap: import heavy libraries inside
the handler. A command never imports `robotdesc.cli` (it sits above the commands).
"""

COMMAND_MODULES: tuple[str, ...] = (
    "robotdesc.commands.lint",
    "robotdesc.commands.expand",
    "robotdesc.commands.rules",
    "robotdesc.commands.inertia",
    "robotdesc.commands.collision",
    "robotdesc.commands.sim",
    "robotdesc.commands.view",
    "robotdesc.commands.report",
    "robotdesc.commands.info",
    "robotdesc.commands.srdf",
    "robotdesc.commands.server",
)
