"""`robotdesc srdf FILE [--samples N] [--seed S] -o robot.srdf`: the self-collision matrix
MoveIt's Setup Assistant computes, without ROS, plus a JSON report of per-pair fractions.

Needs Pinocchio (`pip install '.[kinematics]'`); imported inside the handler.
"""

from __future__ import annotations

import argparse
import logging
import os
import sys
from typing import Any

from robotdesc.commands.info import load_robot
from robotdesc.errors import UsageError
from robotdesc.kinematics.optional import import_pinocchio
from robotdesc.output import check_output, write_output
from robotdesc.progress import progress_for

log = logging.getLogger(__name__)


def register(subparsers: Any, *, common: argparse.ArgumentParser,
             expansion: argparse.ArgumentParser) -> None:
    """Add the `srdf` subcommand."""
    parser = subparsers.add_parser(
        "srdf", parents=[common, expansion], help="self-collision matrix as SRDF (Pinocchio)",
        description="Sample random configurations within the joint limits, check every link "
                    "pair with coal, and write <disable_collisions> for Adjacent, Default, "
                    "Always and Never pairs, as MoveIt's Setup Assistant does "
                    "(install: pip install '.[kinematics]').")
    parser.add_argument("inputs", nargs="+", metavar="FILE | name:=value",
                        help="the URDF/xacro file, then xacro arguments")
    parser.add_argument("-o", "--output", metavar="SRDF",
                        help="write the SRDF here (default: stdout)")
    parser.add_argument("--report", metavar="JSON",
                        help="write the JSON report here (default: next to -o as "
                             "NAME.collisions.json)")
    parser.add_argument("--samples", type=int, default=10000, metavar="N",
                        help="the most random configurations to check (default: 10000); "
                             "sampling stops earlier once no pair changed class over the "
                             "later half of the samples")
    parser.add_argument("--all-samples", action="store_true",
                        help="check all N samples (no adaptive stop)")
    parser.add_argument("--seed", type=int, default=0, metavar="S",
                        help="random seed; the same seed gives the same file (default: 0)")
    parser.add_argument("--jobs", type=int, default=2, metavar="J",
                        help="worker processes (default: 2)")
    parser.add_argument("--always-fraction", type=float, default=0.95, metavar="F",
                        help="pairs colliding in at least this fraction of samples are "
                             "disabled as Always (default: 0.95, as MoveIt)")
    parser.add_argument("--convex", action="store_true",
                        help="check meshes as their convex hulls (faster, coarser)")
    parser.set_defaults(handler=run_srdf)


def run_srdf(ns: argparse.Namespace) -> int:
    """The handler: expand, compute the matrix, write SRDF and report; exit 0 (2 on bad input)."""
    from robotdesc.srdf import compute_matrix, render_report, render_srdf

    import_pinocchio("robotdesc srdf")
    if ns.samples < 0 or ns.jobs < 1 or not 0.0 < ns.always_fraction <= 1.0:
        raise UsageError("--samples must be >= 0, --jobs >= 1, --always-fraction in (0, 1]")
    robot, mesh_path, source, inputs = load_robot(ns, "srdf")
    report_path = ns.report or (_report_name(ns.output) if ns.output else None)
    for target in (ns.output, report_path):
        if target:
            check_output(target, inputs)
    if ns.output and report_path and os.path.realpath(ns.output) == \
            os.path.realpath(report_path):
        raise UsageError("-o and --report name the same file")
    with progress_for(ns, "srdf", total=ns.samples, unit="samples") as bar:
        bar.update(0, detail="preparing the collision scene")
        matrix = compute_matrix(
            robot, mesh_path, samples=ns.samples, seed=ns.seed, workers=ns.jobs,
            always_fraction=ns.always_fraction, convex=ns.convex,
            adaptive=not ns.all_samples, progress=lambda state: bar.update(
                state.samples, state.limit, f"{state.sampled_pairs} pairs still sampled, "
                f"last change at {state.changed_at}"))
    for problem in matrix.problems:
        log.warning("%s: collision of link '%s' left out: %s",
                    problem.where.span if problem.where else source, problem.link,
                    problem.message)
    srdf = render_srdf(matrix)
    if ns.output:
        write_output(ns.output, srdf.encode("utf-8"), inputs)
        log.info("wrote %s (%d pairs disabled)", ns.output, len(matrix.disabled()))
    else:
        sys.stdout.write(srdf)
    if report_path:
        write_output(report_path, render_report(matrix).encode("utf-8"), inputs)
        log.info("wrote %s", report_path)
    return 0


def _report_name(srdf_path: str) -> str | None:
    """NAME.collisions.json beside the SRDF; None when -o is a symlink or a device (e.g.
    /dev/stdout): nothing is written beside it then."""
    if os.path.islink(srdf_path) or (os.path.exists(srdf_path)
                                     and not os.path.isfile(srdf_path)):
        log.info("no JSON report beside %s (not a regular file; use --report)", srdf_path)
        return None
    stem, _ = os.path.splitext(srdf_path)
    return stem + ".collisions.json"
