"""`robotdesc inertia FILE`: per link, the declared inertial against the one of its geometry;
`--suggest` prints corrected `<inertial>` blocks, `--write PATCH` writes them as a diff.

Heavy modules (numpy, the mesh readers) are imported inside the handler.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING

from robotdesc.commands.inputs import single_input
from robotdesc.expansion import expand_file
from robotdesc.inertia.suggest import denser_than_any_material, select_suggestions
from robotdesc.inertia.table import inertia_table, render_table
from robotdesc.linting.inputs import description_inputs, run_inputs
from robotdesc.linting.verdict import inertia_verdict, mark_rows
from robotdesc.mesh.context import MeshContext
from robotdesc.output import check_output, write_output

if TYPE_CHECKING:
    from robotdesc.inertia.mesh_access import MeshAccess
    from robotdesc.inertia.suggest import Suggestion
    from robotdesc.inertia.table import InertiaRow
    from robotdesc.model.elements import Robot


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser], *,
             common: argparse.ArgumentParser, expansion: argparse.ArgumentParser) -> None:
    """Add the `inertia` subcommand."""
    parser = subparsers.add_parser(
        "inertia", parents=[common, expansion], help="compare inertials with the geometry",
        description="Per link: declared mass, centre of mass and principal moments against "
                    "those of its collision (or visual) geometry at uniform density.")
    parser.add_argument("inputs", nargs="+", metavar="FILE | name:=value",
                        help="the URDF/xacro file, then xacro arguments")
    parser.add_argument("--format", choices=("text", "json"), default="text",
                        help="output format (default: text)")
    parser.add_argument("--source", choices=("collision", "visual"),
                        help="geometry to measure (default: config, else collision)")
    parser.add_argument("--suggest", action="store_true",
                        help="print a corrected <inertial> block per link, with the source "
                             "line it replaces")
    parser.add_argument("--write", metavar="PATCH",
                        help="write the suggested blocks as a unified diff against the "
                             "sources to PATCH (the sources are not changed)")
    parser.add_argument("--all", action="store_true",
                        help="suggest for every measured link, not only those that differ "
                             "(links whose lint finding is suppressed too)")
    parser.add_argument("--baseline", metavar="FILE",
                        help="a lint baseline: its recorded findings count as suppressed, as "
                             "in `lint --baseline`")
    parser.set_defaults(handler=run_inertia)


def run_inertia(ns: argparse.Namespace) -> int:
    """The handler: expand, parse, measure, print; exit 0 (2 on unreadable input)."""
    from robotdesc.model.parse import parse_urdf

    single = single_input(ns, "inertia")
    source, config, options = single.source, single.config, single.options
    if ns.write:
        check_output(ns.write, description_inputs(source, config.path))
    expanded = expand_file(source, single.args, options=options)
    robot = parse_urdf(expanded.xml, expanded.source, expanded.files)
    inputs = run_inputs(source, config_path=config.path, expanded=expanded, robot=robot,
                        package_paths=options.package_paths,
                        package_map=options.package_map)
    if ns.write:  # a patch file only: never one of the sources it is made against
        check_output(ns.write, inputs)
    settings = config.meshes if not ns.source else dataclasses.replace(
        config.meshes, inertia_source=ns.source)
    meshes = MeshContext.for_file(robot, source, settings, tuple(options.package_paths),
                                  tuple(options.package_map), use_cache=options.use_cache,
                                  cache_dir=options.cache_dir)
    verdict = inertia_verdict(source, config, args=single.cli_args or None,
                              expand_options=options, baseline=ns.baseline)
    rows = mark_rows(inertia_table(robot, meshes), verdict)
    if (ns.suggest or ns.write) and not ns.all:
        _say_suppressed(rows)
    suggestions = _suggestions(robot, meshes, rows, everything=ns.all) \
        if ns.suggest or ns.write else []
    if ns.suggest or ns.write:
        _say_stand_ins(rows, {s.link for s in suggestions})
    if ns.format == "json":
        document = {"target": source, "source": settings.inertia_source,
                    "links": [row.to_json() for row in rows]}
        if ns.suggest or ns.write:
            document["suggestions"] = [_suggestion_json(s) for s in suggestions]
        sys.stdout.write(json.dumps(document, indent=2) + "\n")
    elif ns.suggest:
        sys.stdout.write(_render_suggestions(suggestions))
    else:
        sys.stdout.write(render_table(rows))
    if ns.write:
        # the edit engine parses the expansion with lxml: only for --write
        from robotdesc.edit.index import ExpandedIndex
        from robotdesc.edit.locate import SourceCache, package_folder
        from robotdesc.inertia.patch import build_patch

        index = ExpandedIndex(expanded.xml, expanded.source, tuple(expanded.files))
        patch = build_patch(suggestions, index, SourceCache(package_folder(source)))
        write_output(ns.write, patch.diff.encode("utf-8"), inputs)
        for reason, links in _by_reason(patch.skipped).items():
            named = ", ".join(f"'{link}'" for link in links[:3])
            more = f" and {len(links) - 3} more" if len(links) > 3 else ""
            sys.stderr.write(f"robotdesc: not patched: link{'s' if len(links) > 1 else ''} "
                             f"{named}{more}: {reason}\n")
        sys.stderr.write(f"robotdesc: wrote {ns.write} ({len(patch.changed)} blocks)\n")
    return 0


def _suggestions(robot: Robot, meshes: MeshAccess, rows: Sequence[InertiaRow],
                 everything: bool) -> list[Suggestion]:
    """Every link whose tensor is wrong (moments or axes), mm meshes scaled: see
    `robotdesc.inertia.suggest.select_suggestions`."""

    return select_suggestions(robot, meshes, rows, everything=everything)


def _by_reason(skipped: Sequence[tuple[str, str]]) -> dict[str, list[str]]:
    """Reason -> the links left out for it (a macro called 212 times gives one line)."""
    found: dict[str, list[str]] = {}
    for link, reason in skipped:
        found.setdefault(reason, []).append(link)
    return found


def _say_suppressed(rows: Sequence[InertiaRow]) -> None:
    """Say how many links get no block because lint's finding on them is suppressed."""
    meant = [row for row in rows if row.suppressed and row.error is not None and row.error > 0.5]
    if meant:
        codes = sorted({code for row in meant for code in row.suppressed})
        sys.stderr.write(f"robotdesc: {len(meant)} links left as they are: lint's "
                         f"{', '.join(codes)} findings on them are suppressed (inline comment, "
                         "config or baseline); --all suggests for them too\n")


def _say_stand_ins(rows: Sequence[InertiaRow], suggested: set[str]) -> None:
    """Name the links left without a suggestion because their geometry cannot be the body."""

    for row in rows:
        if row.link not in suggested and denser_than_any_material(row.density):
            other = "visual" if row.source == "collision" else "collision"
            sys.stderr.write(
                f"robotdesc: link '{row.link}': no suggestion: its {row.source} geometry would "
                f"hold the declared mass at {row.density:.3g} kg/m^3, denser than any "
                f"material (a stand-in, not the body); try --source {other}\n")


def _render_suggestions(suggestions: Sequence[Suggestion]) -> str:
    out = []
    for item in suggestions:
        where = (f"replaces the <inertial> at {item.replaces}" if item.replaces
                 else f"add inside the <link> at {item.link_span}" if item.link_span
                 else "add inside the link")
        out.append(f"<!-- link '{item.link}': {where}"
                   + ("; written inside a xacro macro" if item.in_macro else "") + " -->")
        out.append(item.block)
        out.append("")
    return "\n".join(out) + ("\n" if out else "")


def _suggestion_json(item: Suggestion) -> dict[str, object]:
    return {"link": item.link, "block": item.block,
            "replaces": str(item.replaces) if item.replaces else None,
            "link_at": str(item.link_span) if item.link_span else None,
            "mass_source": item.mass_source, "in_macro": item.in_macro}
