"""`robotdesc collision FILE --method M --out DIR [--check]`: collision geometry, measured.

Exit codes: 0 every link written and within targets and limits (with --check: outputs
current); 1 a link failed, exceeded a limit or the target, or (--check) outputs are stale;
2 the description could not be read, an option is invalid, --out is a file or read-only, or
an output would overwrite a file robotdesc did not write or an input of the run.

Meshes are read under the package rules of lint (`[meshes] allow_absolute_paths` of the
config decides on absolute and file:// paths).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from dataclasses import replace

from robotdesc.collision.limits import ENGINE_LIMITS
from robotdesc.collision.methods import DEFAULT_METHOD, METHOD_TABLE
from robotdesc.collision.options import DEFAULT_BUDGET, METHODS, CollisionOptions
from robotdesc.collision.report import (
    HEADER,
    choice_lines,
    finding_lines,
    table_rows,
    total_line,
)
from robotdesc.commands.inputs import EXIT_FINDINGS, EXIT_OK, single_input
from robotdesc.errors import UsageError
from robotdesc.expansion import expand_file
from robotdesc.linting.inputs import run_inputs
from robotdesc.mesh.locate import MeshLocator
from robotdesc.output import check_output_dir
from robotdesc.progress import progress_for
from robotdesc.report.table import render_table


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser], *,
             common: argparse.ArgumentParser, expansion: argparse.ArgumentParser) -> None:
    parser = subparsers.add_parser(
        "collision", parents=[common, expansion], help="make collision meshes, measured",
        description="Make collision geometry per link (decimate, hull, coacd, primitive, "
                    "auto) from the visual meshes, measure its fidelity, write it to DIR.")
    parser.add_argument("inputs", nargs="+", metavar="FILE | name:=value",
                        help="the description, then xacro arguments")
    parser.add_argument("--method", default=DEFAULT_METHOD, choices=METHODS,
                        help="; ".join(f"{m.name}: {m.summary}" for m in METHOD_TABLE)
                        + f" (default {DEFAULT_METHOD})")
    parser.add_argument("--budget", type=int, default=DEFAULT_BUDGET, metavar="TRIANGLES",
                        help="auto: triangles of the whole robot's collision (primitives "
                             f"count none; 0: no budget; default {DEFAULT_BUDGET:,}, under "
                             "the Engineer papers' hand-made 5,644)")
    parser.add_argument("--no-contact", action="append", default=[], metavar="LINKS",
                        help="auto: leave these links (comma-separated shell patterns, "
                             "e.g. '*_track_link') out of contact: no <collision>, e.g. a "
                             "belt that touches the ground only through its wheels (also "
                             "[meshes] no-contact in the config)")
    parser.add_argument("--out", metavar="DIR", help="output folder (required unless "
                        "only reporting with --dry-run)")
    parser.add_argument("--check", action="store_true",
                        help="do not write: exit 1 when the outputs in DIR are missing or stale")
    parser.add_argument("--dry-run", action="store_true", help="report only, write nothing")
    parser.add_argument("--link", action="append", default=None, metavar="NAME",
                        help="only this link (repeatable)")
    parser.add_argument("--source", choices=("visual", "collision"), default="visual",
                        help="derive from the visual (default) or the collision meshes")
    parser.add_argument("--ratio", type=float, default=0.02,
                        help="decimate: share of faces kept (default 0.02)")
    parser.add_argument("--faces", type=int, help="decimate: face budget per link")
    parser.add_argument("--decimator", choices=("meshoptimizer", "fast-simplification"),
                        default="meshoptimizer",
                        help="decimate: engine tried first; the other is the fallback "
                             "(default meshoptimizer)")
    parser.add_argument("--no-adapt", dest="adapt", action="store_false",
                        help="keep the --ratio budget and hulls as made: results over "
                             "--target or the engine's limits are findings only (default: "
                             "decimate raises its budget until --target is met, hulls are "
                             "reduced to the engine's vertex limit)")
    parser.add_argument("--threshold", type=float, default=0.1,
                        help="coacd: concavity threshold (default 0.1)")
    parser.add_argument("--max-hulls", type=int, default=16,
                        help="coacd: hulls per link, -1 for no limit (default 16)")
    parser.add_argument("--hull-vertices", type=int, default=64,
                        help="coacd: vertices per hull (default 64)")
    parser.add_argument("--coacd-input-faces", type=int, default=2000, metavar="N",
                        help="coacd: decimate a larger mesh to N faces before CoACD (faster; "
                             "fidelity is measured against the original); 0: never "
                             "(default 2000)")
    parser.add_argument("--seed", type=int, default=0, help="coacd: random seed (default 0)")
    parser.add_argument("--primitives", default="box,cylinder,sphere,capsule",
                        help="primitive: kinds tried (comma-separated)")
    parser.add_argument("--target", type=float, default=1.0, metavar="PERCENT",
                        help="fidelity target: Hausdorff distance in %% of the link's "
                             "bounding diagonal; auto: in %% of the robot's largest link's, "
                             "one tolerance in mm for every link (default 1)")
    parser.add_argument("--engine", choices=("physx", "mujoco", "bullet"), default="physx",
                        help="engine limits to check (default physx)")
    parser.add_argument("--limit-hulls", type=int, help="override the engine's hulls per link")
    parser.add_argument("--limit-hull-vertices", type=int,
                        help="override the engine's vertices per hull")
    parser.add_argument("--jobs", "-j", type=int, help="worker processes (default: all cores)")
    parser.add_argument("--scheduler", metavar="ADDRESS",
                        help="run the per-link work on a Dask cluster at ADDRESS, e.g. "
                             "tcp://host:8786; needs robotdesc[dask]")
    parser.add_argument("--mesh-timeout", type=float, default=300.0, metavar="SECONDS",
                        help="wall-clock limit per link (default 300)")
    parser.add_argument("--format", choices=("text", "json"), default="text")
    parser.add_argument("--into-source-dir", action="store_true",
                        help="allow DIR to be a folder holding source meshes")
    parser.set_defaults(handler=run)


def run(ns: argparse.Namespace) -> int:
    """The handler (SIGTERM while links are made: see `collision.worker.run_tasks`)."""
    return _run(ns)


def _run(ns: argparse.Namespace) -> int:
    from robotdesc.model.parse import parse_urdf

    single = single_input(ns, "collision")
    if not ns.out and not ns.dry_run:
        raise UsageError("--out DIR is required (or --dry-run)")
    limits = ENGINE_LIMITS[ns.engine]
    if ns.limit_hulls is not None or ns.limit_hull_vertices is not None:
        limits = replace(limits, name="custom",
                         max_hulls=ns.limit_hulls or limits.max_hulls,
                         max_hull_vertices=ns.limit_hull_vertices or limits.max_hull_vertices)
    try:
        options = CollisionOptions(
            method=ns.method, ratio=ns.ratio, faces=ns.faces, decimator=ns.decimator,
            adapt=ns.adapt, threshold=ns.threshold, coacd_input_faces=ns.coacd_input_faces,
            max_hulls=ns.max_hulls, hull_vertices=ns.hull_vertices, seed=ns.seed,
            primitives=tuple(p.strip() for p in ns.primitives.split(",") if p.strip()),
            target_percent=ns.target, source=ns.source, mesh_timeout_s=ns.mesh_timeout,
            budget_triangles=ns.budget, limits=limits,
            no_contact=_no_contact(ns.no_contact, single.config.meshes.no_contact)
        ).validated()
    except ValueError as error:
        raise UsageError(str(error)) from None
    if ns.jobs is not None and ns.jobs < 1:
        raise UsageError("--jobs must be at least 1")
    writing = bool(ns.out) and not ns.dry_run and not ns.check
    if writing:
        check_output_dir(ns.out)
    expanded = expand_file(single.source, single.args, options=single.options)
    robot = parse_urdf(expanded.xml, expanded.source, expanded.files)
    package_paths = single.options.package_paths
    package_map = single.options.package_map
    allow_absolute = single.config.meshes.allow_absolute_paths

    if ns.check:
        from robotdesc.collision.check import check_outputs
        from robotdesc.collision.generate import plan_links

        plan = plan_links(robot, options, package_paths, package_map, ns.link,
                          use_cache=not ns.no_cache, allow_absolute_paths=allow_absolute)
        stale = check_outputs(plan, ns.out, every_link=ns.link is None)
        for item in stale:
            sys.stdout.write(f"{item.subject}: {item.reason}\n")
        if not stale:
            sys.stdout.write(f"collision outputs in {ns.out} are up to date\n")
        return EXIT_FINDINGS if stale else EXIT_OK

    from robotdesc.collision.generate import generate_collision

    try:
        with progress_for(ns, "collision", unit="links") as bar:
            result = generate_collision(robot, options=options, method=options.method,
                                        package_paths=package_paths, package_map=package_map,
                                        links=ns.link, jobs=ns.jobs,
                                        use_cache=not ns.no_cache, progress=bar.update,
                                        scheduler=ns.scheduler,
                                        allow_absolute_paths=allow_absolute)
    except ValueError as error:
        raise UsageError(str(error)) from None
    if writing:
        from robotdesc.collision.output import write_outputs
        from robotdesc.collision.sources import link_sources

        found = link_sources(robot, options.source,
                             MeshLocator.for_robot(robot, package_paths, package_map,
                                                   allow_absolute=allow_absolute))
        dirs = tuple(sorted({os.path.dirname(p) for s in found for p in s.mesh_paths}))
        inputs = run_inputs(single.source, config_path=single.config.path,
                            expanded=expanded, robot=robot, package_paths=package_paths,
                            package_map=package_map)
        write_outputs(result, expanded.xml, ns.out, from_xacro=expanded.from_xacro,
                      source_dirs=dirs, allow_source_dir=ns.into_source_dir, inputs=inputs)
    if ns.format == "json":
        sys.stdout.write(json.dumps(result.to_dict(), indent=2) + "\n")
    else:
        sys.stdout.write(render_table(HEADER, table_rows(result), wrap=0,
                                      right=(4, 5, 6, 7, 8, 9)))
        sys.stdout.write("".join(line + "\n" for line in (*choice_lines(result),
                                                           *finding_lines(result),
                                                           total_line(result))))
    return EXIT_FINDINGS if result.failed else EXIT_OK


def _no_contact(given: list[str], configured: tuple[str, ...]) -> tuple[str, ...]:
    """The links left out of contact: `--no-contact` (comma-separated, repeatable) and the
    config's `[meshes] no-contact`, each pattern once."""
    patterns = [p.strip() for text in given for p in text.split(",") if p.strip()]
    return tuple(dict.fromkeys([*configured, *patterns]))
