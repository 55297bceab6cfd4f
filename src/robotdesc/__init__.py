"""robotdesc: expand xacro without ROS, load URDF into a strict model, lint it.

The public API::

    import robotdesc
    robot = robotdesc.load("robot.urdf.xacro", args={"prefix": "left_"})
    expanded = robotdesc.expand("robot.urdf.xacro")      # URDF bytes + where each element came from
    result = robotdesc.lint("robot.urdf.xacro")          # diagnostics, like `robotdesc lint`
    text = robotdesc.to_urdf("robot.urdf.xacro")         # clean URDF text, as `robotdesc expand`
    page = robotdesc.html_report(result)                 # the page of `robotdesc report`

Heavy modules (xacro, lxml, the rules) are imported on first use, so `import robotdesc` is cheap
(even `dataclasses` is: `robotdesc --version` starts within 2x the bare interpreter).
"""

from __future__ import annotations

import os
import sys
from typing import TYPE_CHECKING, Any, Literal, Mapping, Sequence

from robotdesc._version import __version__

if "IPython" in sys.modules:  # a notebook: results render as the report's tables
    from robotdesc.report import notebook as _notebook

    _notebook.register()

if TYPE_CHECKING:  # pragma: no cover
    from robotdesc.collision.result import CollisionResult
    from robotdesc.config import Config
    from robotdesc.expansion.result import Expanded
    from robotdesc.inertia.table import InertiaTable
    from robotdesc.linting.result import LintResult
    from robotdesc.model.elements import Robot
    from robotdesc.view.show import View


__all__ = ["__version__", "expand", "generate_collision", "html_report", "json_report", "lint",
           "load", "mesh_inertia", "show", "to_urdf", "to_yourdfpy"]


def generate_collision(robot: "Robot", method: str = "decimate",
                       **options: Any) -> "CollisionResult":
    """Collision geometry per link, measured; see `robotdesc.collision.generate`.

    Returns a `CollisionResult` (new geometry and a per-link report); `robot` is not
    modified. Scripts must guard their entry point (`if __name__ == "__main__":`), as the
    work runs in worker processes.
    """
    from robotdesc.collision.generate import generate_collision as run

    return run(robot, method, **options)


def to_urdf(source: "str | Expanded", args: Mapping[str, str] | None = None, *,
            package_paths: Sequence[str] = ()) -> str:
    """Clean URDF text, as `robotdesc expand` writes it: indented, with a banner, and
    without robotdesc's internal provenance attributes.

    Args:
        source: a description file (expanded first), or an `Expanded` from `expand`.
        args: xacro arguments (with a file only).
        package_paths: directories to search for ROS packages first (with a file only).

    Raises:
        robotdesc.errors.InputError: the file could not be expanded.
    """
    from robotdesc.model.write import urdf_text

    expanded = expand(source, args, package_paths=package_paths) \
        if isinstance(source, str) else source
    return urdf_text(expanded.xml, expanded.source).decode("utf-8")


def json_report(*results: "LintResult") -> dict[str, object]:
    """The document of `robotdesc lint --format json` for `lint` results, as a dict."""
    from robotdesc.report.json import report_dict

    return report_dict(results)


def html_report(result: "LintResult", collision: "CollisionResult | None" = None, *,
                joint_values: Mapping[str, float] | None = None, view: bool = True,
                package_paths: Sequence[str] = ()) -> str:
    """The self-contained HTML page of `robotdesc report` for a `lint` result.

    Args:
        result: what `robotdesc.lint` returned (it carries the parsed robot).
        collision: a `CollisionResult` from `generate_collision` to compare, if any.
        joint_values: the configuration of the 3D view (rad or m).
        view: include the 3D view.
        package_paths: directories to search for ROS packages first.

    Returns:
        The page (write it with `Path(...).write_text(page, encoding="utf-8")`).
    """
    import dataclasses

    from robotdesc.config import discover_config
    from robotdesc.report.html import render_html_report
    from robotdesc.report.html_data import collect_report

    config = discover_config(result.target)
    data = collect_report(result, package_paths=package_paths,
                          package_map=tuple(config.packages), joint_values=joint_values,
                          mesh_settings=config.meshes, view=view)
    if collision is not None:
        data = dataclasses.replace(data, collision=collision)
    return render_html_report(data)


def expand(path: str, args: Mapping[str, str] | None = None, *,
           package_paths: Sequence[str] = (), trusted: bool = False,
           use_cache: bool = True) -> "Expanded":
    """Expand a .xacro (or read a plain .urdf) with robotdesc's own package resolution.

    Args:
        path: the description file.
        args: xacro arguments (`name:=value` on the command line).
        package_paths: directories to search for ROS packages first.
        trusted: lift the sandbox limits (only for your own files).
        use_cache: reuse a cached expansion of unchanged inputs.

    Raises:
        robotdesc.errors.InputError: the file could not be expanded.
    """
    from robotdesc.expansion import ExpandOptions, expand_file

    options = ExpandOptions(package_paths=tuple(package_paths), trusted=trusted,
                            use_cache=use_cache)
    return expand_file(path, dict(args or {}), options=options)


def load(path: str, args: Mapping[str, str] | None = None,
         package_paths: Sequence[str] = ()) -> "Robot":
    """Expand (when xacro) and strictly parse a description into a `Robot`.

    Raises:
        robotdesc.errors.InputError: the file could not be expanded or parsed.
    """
    from robotdesc.model.parse import parse_urdf

    expanded = expand(path, args, package_paths=package_paths)
    return parse_urdf(expanded.xml, expanded.source, expanded.files)


def mesh_inertia(path: str, args: Mapping[str, str] | None = None, *,
                 source: Literal["collision", "visual"] | None = None,
                 package_paths: Sequence[str] = ()) -> "InertiaTable":
    """Declared against mesh-derived mass, centre of mass and principal moments per link.

    The MeshLab "Compute Geometric Measures" step for every link at once: each link's
    geometry (collision by default, or `source="visual"`) at uniform density, scaled to the
    declared mass, in the link frame.

    Args:
        path: the description file (xacro or URDF).
        args: xacro arguments.
        source: "collision" or "visual" (default: the config's, else collision).
        package_paths: folders searched for ROS packages first.

    Returns:
        An `InertiaTable` (renders as a table in Jupyter; `.rows`, `.to_dict()`). A row whose
        link's inertia finding lint suppresses (inline comment, per-file ignore) has
        `suppressed` set to the codes, as `robotdesc inertia` shows it.

    Raises:
        UsageError: `source` is neither "collision" nor "visual".
    """
    import dataclasses

    from robotdesc.config import discover_config
    from robotdesc.errors import UsageError
    from robotdesc.expansion import ExpandOptions
    from robotdesc.inertia.table import InertiaTable, inertia_table
    from robotdesc.linting.verdict import inertia_verdict, mark_rows
    from robotdesc.mesh.context import MeshContext
    from robotdesc.model.parse import parse_urdf

    if source not in (None, "collision", "visual"):
        raise UsageError(f"source must be 'collision' or 'visual', not {source!r}")
    config = discover_config(path)
    expanded = expand(path, {**dict(config.args), **dict(args or {})},
                      package_paths=package_paths)
    robot = parse_urdf(expanded.xml, expanded.source, expanded.files)
    settings = config.meshes if source is None else dataclasses.replace(
        config.meshes, inertia_source=source)
    meshes = MeshContext.for_file(robot, expanded.source, settings, tuple(package_paths),
                                  tuple(config.packages))
    verdict = inertia_verdict(path, config, args=args,
                              expand_options=ExpandOptions(package_paths=tuple(package_paths)))
    return InertiaTable(expanded.source, settings.inertia_source,
                        tuple(mark_rows(inertia_table(robot, meshes), verdict)))


def lint(path: str, args: Mapping[str, str] | None = None, *,
         select: Sequence[str] | None = None, ignore: Sequence[str] = (),
         config: "Config | str | None" = None, package_paths: Sequence[str] = (),
         trusted: bool = False) -> "LintResult":
    """Lint one description as `robotdesc lint` does.

    Args:
        path: the description file.
        args: xacro arguments (override the config's `args`).
        select: rule selectors replacing the config's `select`.
        ignore: rule selectors added to the config's `ignore`.
        config: a `Config`, a config file path, or None to discover one from `path`.
        package_paths: directories to search for ROS packages first.
        trusted: lift the sandbox limits (only for your own files).

    Returns:
        A `LintResult` (`.diagnostics`, `.counts`; renders as a table in Jupyter;
        `robotdesc.json_report(result)` gives the JSON document).

    Raises:
        UsageError: a selector matches no rule (as `--select`/`--ignore` on the command line).
    """
    from robotdesc.config import load_config
    from robotdesc.expansion import ExpandOptions
    from robotdesc.linting.driver import lint_file
    from robotdesc.rules.catalog import all_rules
    from robotdesc.rules.select import check_selectors

    check_selectors(select or (), all_rules(), "select")
    check_selectors(ignore, all_rules(), "ignore")
    if isinstance(config, str):
        config = load_config(config)
    options = ExpandOptions(package_paths=tuple(package_paths), trusted=trusted)
    return lint_file(path, config, args=args, expand_options=options, select=select,
                     ignore=ignore)


def show(target: "str | os.PathLike[str] | Robot | LintResult",
         joint_values: Mapping[str, float] | None = None, **options: Any) -> "View":
    """A 3D view of a robot (a file, a `Robot` or a `LintResult`) at a configuration.

    Returns a `robotdesc.view.show.View`: displayed inline in Jupyter, `.save("robot.html")`
    writes the self-contained page. Options: see `robotdesc.view.show.show`.
    """
    from robotdesc.view.show import show as run

    return run(target, joint_values, **options)


def to_yourdfpy(source: "str | os.PathLike[str] | LintResult | Expanded", *,
                package_paths: Sequence[str] = (), load_meshes: bool = True,
                load_collision_meshes: bool = False, **xacro_args: str) -> Any:
    """A `yourdfpy.URDF` of the expanded description (extra `yourdfpy`), its meshes resolved
    by robotdesc's package resolver, so forward kinematics, `.scene` and `.show()` work
    without ROS.

    Args:
        source: a description file (expanded with the config's `args` and `xacro_args`), a
            `LintResult` from `lint`, or an `Expanded` from `expand`.
        package_paths: folders searched for ROS packages first.
        load_meshes: load the visual meshes (the scene); collision meshes with
            `load_collision_meshes`.
        **xacro_args: xacro arguments (with a file only), e.g. `with_gripper="false"`.

    Raises:
        robotdesc.errors.InputError: the file could not be expanded or parsed.
        robotdesc.errors.UsageError: yourdfpy is not installed, or arguments with a result.
    """
    from robotdesc.config import discover_config
    from robotdesc.errors import UsageError
    from robotdesc.expansion.result import Expanded as ExpandedType
    from robotdesc.kinematics.yourdfpy_urdf import yourdfpy_urdf
    from robotdesc.model.parse import parse_urdf

    if isinstance(source, (str, os.PathLike)):
        path = os.fspath(source)
        config = discover_config(path)
        expanded = expand(path, {**dict(config.args), **xacro_args}, package_paths=package_paths)
        robot = None
    elif xacro_args:
        raise UsageError("xacro arguments go with a file, not with an expanded result: "
                         + ", ".join(sorted(xacro_args)))
    elif isinstance(source, ExpandedType):
        expanded, robot, config = source, None, discover_config(source.source)
    else:  # a LintResult (its expansion may have been dropped: expand its target again)
        config = discover_config(source.target)
        expanded = source.expanded if source.expanded is not None else expand(
            source.target, dict(source.args) or dict(config.args), package_paths=package_paths)
        robot = source.robot if source.expanded is not None else None
    if robot is None:
        robot = parse_urdf(expanded.xml, expanded.source, expanded.files)
    return yourdfpy_urdf(expanded, robot, package_paths=package_paths,
                         package_map=tuple(config.packages),
                         allow_absolute=config.meshes.allow_absolute_paths,
                         load_meshes=load_meshes, load_collision_meshes=load_collision_meshes)
