"""`robotdesc report FILE -o report.html`: one self-contained HTML page with the findings
grouped by link, the 3D view, the inertia table, the collision table and plots.

Exit codes: 0 written (findings do not fail a report; use `robotdesc lint` for a gate),
2 the input could not be read.
"""

from __future__ import annotations

import argparse
import sys
import time
from typing import Any

from robotdesc.collision.options import METHODS
from robotdesc.commands.view import add_view_arguments, load_target
from robotdesc.config import discover_config, load_config
from robotdesc.output import write_output
from robotdesc.progress import progress_for
from robotdesc.view.forward import parse_assignments


def register(subparsers: Any, *, common: argparse.ArgumentParser,
             expansion: argparse.ArgumentParser) -> None:
    """Add the `report` subcommand."""
    parser = subparsers.add_parser(
        "report", parents=[common, expansion], help="write an HTML report",
        description="Write one self-contained HTML page: findings grouped by link, a 3D view, "
                    "the inertia table (declared against geometry), the collision table and "
                    "plots (plots need matplotlib: pip install '.[report]').")
    add_view_arguments(parser)
    parser.add_argument("-o", "--output", required=True, metavar="HTML",
                        help="the page to write")
    parser.add_argument("--collision", metavar="METHOD",
                        choices=METHODS,
                        help="also generate collision geometry with METHOD and report how it "
                             "compares (nothing is written besides the page)")
    parser.add_argument("--jobs", "-j", type=int, default=None, metavar="N",
                        help="worker processes for --collision (default: all cores)")
    parser.add_argument("--no-view", action="store_true", help="leave out the 3D view")
    parser.set_defaults(handler=run_report)


def run_report(ns: argparse.Namespace) -> int:
    """The handler: lint, gather, render, write."""
    from robotdesc.report.html import render_html_report
    from robotdesc.report.html_data import collect_report

    started = time.perf_counter()
    values = parse_assignments(ns.q)
    with progress_for(ns, "report") as bar:
        bar.update(0, detail="linting")
        _, result, options, inputs = load_target(ns, lint=True)
        config = load_config(ns.config) if ns.config else discover_config(result.target)
        bar.update(0, detail="3D scene, inertia" + (f", collision ({ns.collision})"
                                                     if ns.collision else ""))
        data = collect_report(result, package_paths=options.package_paths,
                              package_map=options.package_map, joint_values=values,
                              max_faces=ns.max_faces, mesh_settings=config.meshes,
                              collision_method=ns.collision, jobs=ns.jobs,
                              view=not ns.no_view)
        bar.update(0, detail="rendering the page")
        page = render_html_report(data).encode("utf-8")
    write_output(ns.output, page, inputs)
    sys.stderr.write(f"robotdesc: wrote {ns.output} ({len(page) / 1e6:.2f} MB, "
                     f"{len(result.diagnostics)} findings; "
                     f"{time.perf_counter() - started:.1f} s)\n")
    return 0
