"""`robotdesc info FILE`: links, joints by type, degrees of freedom, mimic joints, total mass,
centre of mass (at zero and at `--q name=value ...`) and bounding box; table or JSON.

Needs Pinocchio (`pip install '.[kinematics]'`); imported inside the handler.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Iterable
from typing import TYPE_CHECKING

from robotdesc.commands.inputs import single_input
from robotdesc.expansion import expand_file
from robotdesc.kinematics.optional import import_pinocchio
from robotdesc.linting.inputs import run_inputs
from robotdesc.mesh.locate import MeshLocator
from robotdesc.printable import printable
from robotdesc.progress import progress_for
from robotdesc.view.forward import parse_assignments

if TYPE_CHECKING:
    from robotdesc.kinematics.info import RobotInfo
    from robotdesc.kinematics.urdf_text import MeshPath
    from robotdesc.model.elements import Robot
    from robotdesc.output import RunInputs


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser], *,
             common: argparse.ArgumentParser, expansion: argparse.ArgumentParser) -> None:
    """Add the `info` subcommand."""
    parser = subparsers.add_parser(
        "info", parents=[common, expansion], help="kinematic and mass summary (Pinocchio)",
        description="Links, joints by type, degrees of freedom, mimic joints, total mass, "
                    "centre of mass and bounding box, computed with Pinocchio "
                    "(install: pip install '.[kinematics]').")
    parser.add_argument("inputs", nargs="+", metavar="FILE | name:=value",
                        help="the URDF/xacro file, then xacro arguments")
    parser.add_argument("--q", action="append", default=[], metavar="JOINT=VALUE",
                        help="a joint position (rad or m) for the centre of mass at a "
                             "configuration; repeatable")
    parser.add_argument("--format", choices=("text", "json"), default="text",
                        help="output format (default: text)")
    parser.set_defaults(handler=run_info)


def load_robot(ns: argparse.Namespace, verb: str) -> tuple[Robot, MeshPath, str, RunInputs]:
    """Expand and parse the one input file; returns (robot, mesh resolver, source path,
    the files the run read as `robotdesc.output.RunInputs`)."""
    from robotdesc.model.parse import parse_urdf

    single = single_input(ns, verb)
    options = single.options
    expanded = expand_file(single.source, single.args, options=options)
    robot = parse_urdf(expanded.xml, expanded.source, expanded.files)
    meshes = MeshLocator.for_robot(robot, options.package_paths, options.package_map,
                                   allow_absolute=single.config.meshes.allow_absolute_paths,
                                   origin=expanded.source)
    inputs = run_inputs(single.source, config_path=single.config.path, expanded=expanded,
                        robot=robot, package_paths=options.package_paths,
                        package_map=options.package_map)
    return robot, meshes.path, single.source, inputs


def run_info(ns: argparse.Namespace) -> int:
    """The handler: expand, build with Pinocchio, print; exit 0 (2 on unusable input)."""
    from robotdesc.kinematics.info import robot_info

    import_pinocchio("robotdesc info")
    positions = parse_assignments(ns.q)
    with progress_for(ns, "info") as bar:
        bar.update(0, detail="expanding and parsing")
        robot, mesh_path, _, _ = load_robot(ns, "info")
        bar.update(0, detail=f"building the model of {len(robot.links)} links (Pinocchio)")
        info = robot_info(robot, mesh_path, positions or None)
    if ns.format == "json":
        sys.stdout.write(json.dumps(info.to_dict(), indent=2) + "\n")
    else:
        sys.stdout.write(render_info(info))
    return 0


def render_info(info: RobotInfo) -> str:
    """The info as an aligned two-column table."""
    def vec(values: Iterable[float]) -> str:
        return "(" + ", ".join(f"{v:.4f}" for v in values) + ") m"

    rows = [("robot", info.name), ("links", str(info.links)),
            ("joints", ", ".join(f"{n} {t}" for t, n in info.joints_by_type) or "none"),
            ("degrees of freedom", str(info.dof)),
            ("mimic joints", ", ".join(f"{m.joint} = {m.multiplier:g} * {m.driver} "
                                       f"+ {m.offset:g}" for m in info.mimic) or "none"),
            ("total mass", f"{info.total_mass:.4f} kg"),
            ("centre of mass at zero", vec(info.com_zero))]
    if info.com_at is not None:
        rows.append(("centre of mass at --q", vec(info.com_at)))
    box = f"{vec(info.bounds[0])} .. {vec(info.bounds[1])}" if info.bounds else \
        "no collision geometry" if not info.left_out else "no readable collision geometry"
    if info.left_out:
        box += (f" ({len(info.left_out)} <collision> left out; first: {info.left_out[0]})")
    rows.append(("bounding box (collision)", box))
    width = max(len(label) for label, _ in rows)
    return "".join(f"{label.ljust(width)}  {printable(value)}\n" for label, value in rows)
