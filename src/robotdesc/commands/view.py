"""`robotdesc view FILE -o robot.html [--q JOINT=VALUE]`: a self-contained 3D view.

The page holds the robot at the given configuration, its visual and collision geometry, the
equivalent inertia box of each link and the links with lint findings highlighted; it opens
from disk with no network. Exit codes: 0 written, 2 the input could not be read.
"""

from __future__ import annotations

import argparse
import logging
import sys
import time
from typing import Any

from robotdesc.commands.inputs import single_input
from robotdesc.errors import UsageError
from robotdesc.expansion import expand_file
from robotdesc.linting.driver import lint_file
from robotdesc.linting.inputs import description_inputs, run_inputs
from robotdesc.output import check_output, write_output
from robotdesc.view.forward import parse_assignments

log = logging.getLogger(__name__)


def register(subparsers: Any, *, common: argparse.ArgumentParser,
             expansion: argparse.ArgumentParser) -> None:
    """Add the `view` subcommand."""
    parser = subparsers.add_parser(
        "view", parents=[common, expansion], help="write a 3D view as one HTML page",
        description="Write a self-contained HTML page (no network needed) showing the robot "
                    "at a configuration: visual and collision geometry, equivalent inertia "
                    "boxes, links with lint findings highlighted.")
    add_view_arguments(parser)
    parser.add_argument("-o", "--output", required=True, metavar="HTML",
                        help="the page to write")
    parser.add_argument("--show", default="visual,findings", metavar="WHAT",
                        help="shown when the page opens, comma-separated from visual, "
                             "collision, inertia, findings (default: visual,findings); all "
                             "can be toggled in the page")
    parser.add_argument("--no-lint", action="store_true",
                        help="do not lint (no findings highlighted; faster)")
    parser.set_defaults(handler=run_view)


def add_view_arguments(parser: argparse.ArgumentParser) -> None:
    """The inputs, `--q` and `--max-faces` (shared with `robotdesc report`)."""
    parser.add_argument("inputs", nargs="+", metavar="FILE | name:=value",
                        help="the URDF/xacro file, then xacro arguments")
    parser.add_argument("--q", action="append", default=[], metavar="JOINT=VALUE",
                        help="a joint position (rad or m); repeatable; others at 0 or their "
                             "nearest limit, mimic joints follow")
    parser.add_argument("--max-faces", type=int, default=None, metavar="N",
                        help="display budget per mesh file (larger meshes are reduced for "
                             "display only; default 12000)")


def load_target(ns: argparse.Namespace, lint: bool = True) -> tuple[Any, Any, Any, Any]:
    """Expand and parse the one input, linted when `lint`: (robot, LintResult or None,
    the expansion options with the config's packages, the files the run read).

    Raises:
        UsageError: not exactly one file, or a bad option.
        OutputError: `ns.output` is an input of the run.
    """
    single = single_input(ns, ns.command)
    source, options = single.source, single.options
    check_output(ns.output, description_inputs(source, single.config.path))
    if ns.max_faces is not None and ns.max_faces < 1:
        raise UsageError("--max-faces must be at least 1")
    if lint:
        result = lint_file(source, single.config, args=single.cli_args or None,
                           expand_options=options)
        robot, expanded = result.robot, result.expanded
    else:
        from robotdesc.model.parse import parse_urdf

        result = None
        expanded = expand_file(source, single.args, options=options)
        robot = parse_urdf(expanded.xml, expanded.source, expanded.files)
    inputs = run_inputs(source, config_path=single.config.path, expanded=expanded,
                        robot=robot, package_paths=options.package_paths,
                        package_map=options.package_map)
    return robot, result, options, inputs


def run_view(ns: argparse.Namespace) -> int:
    """The handler: lint, build the scene, write the page."""
    from robotdesc.view.show import SHOW_OPTIONS, show

    started = time.perf_counter()
    visible = tuple(part.strip() for part in ns.show.split(",") if part.strip())
    unknown = [v for v in visible if v not in SHOW_OPTIONS]
    if unknown:
        raise UsageError(f"--show: unknown '{unknown[0]}' (choose from "
                         f"{', '.join(SHOW_OPTIONS)})")
    values = parse_assignments(ns.q)
    robot, result, options, inputs = load_target(ns, lint=not ns.no_lint)
    view = show(result if result is not None else robot, values,
                package_paths=options.package_paths, package_map=options.package_map,
                visible=visible,
                max_faces=ns.max_faces)
    page = view.html().encode("utf-8")
    write_output(ns.output, page, inputs)
    doc = view.document
    flagged = sum(1 for link in doc["links"] if link["findings"])
    sys.stderr.write(f"robotdesc: wrote {ns.output} ({len(page) / 1e6:.2f} MB: "
                     f"{len(doc['links'])} links, {len(doc['instances'])} shapes, "
                     f"{flagged} links with findings, {len(doc['problems'])} shapes not shown; "
                     f"{time.perf_counter() - started:.1f} s)\n")
    for problem in doc["problems"]:
        log.warning("%s %s[%d] not shown: %s", problem["link"], problem["kind"],
                    problem["index"], problem["message"])
    return 0
