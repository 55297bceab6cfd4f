"""Subcommands beyond lint/expand/rules/rule, one module each.

Each module listed here has `register(subparsers, *, common, expansion)` that adds its parser
(with `common` and, when it reads descriptions, `expansion` as parents) and sets `handler`
to a function `(argparse.Namespace) -> int` returning the exit code. Module import must be
cheap: import heavy libraries inside the handler.
"""

COMMAND_MODULES: tuple[str, ...] = (
    "robotdesc.commands.inertia",
    "robotdesc.commands.collision",
    "robotdesc.commands.sim",
    "robotdesc.commands.view",
    "robotdesc.commands.report",
    "robotdesc.commands.info",
    "robotdesc.commands.srdf",
    "robotdesc.commands.server",
)
