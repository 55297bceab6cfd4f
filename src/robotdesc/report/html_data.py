"""Gather what the HTML report shows: the lint result, the display scene, the inertia table
and (on request) a collision generation run. The I/O edge of the report; rendering is in
html.py."""

from __future__ import annotations

import logging
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from robotdesc.errors import UsageError
from robotdesc.expansion.packages import package_lookup
from robotdesc.inertia.table import inertia_table
from robotdesc.linting.verdict import mark_rows, result_verdict
from robotdesc.mesh.context import MeshContext
from robotdesc.mesh.locate import MeshLocator
from robotdesc.mesh.resolve import PackageLookup
from robotdesc.mesh.settings import MeshSettings
from robotdesc.model.elements import Robot
from robotdesc.view.scene import Scene

if TYPE_CHECKING:
    from robotdesc.collision.options import CollisionOptions
    from robotdesc.collision.result import CollisionResult
    from robotdesc.inertia.table import InertiaRow
    from robotdesc.linting.result import LintResult

log = logging.getLogger(__name__)


@dataclass(frozen=True, eq=False)
class ReportData:
    """Everything one report page is made of.

    Attributes:
        result: the `LintResult` (its `diagnostics`).
        robot: its model (`result.robot`, which a report needs).
        scene: the display scene (None: no 3D view).
        inertia_rows: the inertia table (`robotdesc.inertia.table.InertiaRow`s); None when
            it was not computed.
        collision: a `CollisionResult` from `generate_collision`, when one was run.
        notes: what could not be included, and why.
        seconds: time spent gathering (s).
    """

    result: LintResult
    robot: Robot
    scene: Scene | None
    inertia_rows: tuple[InertiaRow, ...] | None = None
    collision: CollisionResult | None = None
    notes: tuple[str, ...] = ()
    seconds: float = 0.0


def collect_report(result: LintResult, *, package_paths: Sequence[str] = (),
                   package_map: Sequence[tuple[str, str]] = (),
                   joint_values: Mapping[str, float] | None = None,
                   max_faces: int | None = None, mesh_settings: MeshSettings | None = None,
                   collision_method: str | None = None,
                   collision_options: CollisionOptions | None = None,
                   jobs: int | None = None, view: bool = True) -> ReportData:
    """Build the scene and the inertia table of a linted robot, and optionally generate
    collision geometry to compare with.

    Args:
        result: a `LintResult` with a parsed `robot`.
        package_paths, package_map: where `package://` meshes are looked up first.
        joint_values: the configuration of the 3D view (rad or m).
        max_faces: display budget per mesh file.
        mesh_settings: `robotdesc.mesh.settings.MeshSettings` (default: the defaults).
        collision_method: run `generate_collision` with this method ("decimate", "hull",
            "coacd", "primitive", "auto"); None: do not.
        collision_options: a `robotdesc.collision.CollisionOptions`, if any.
        jobs: worker processes for collision generation.
        view: build the 3D scene.

    Raises:
        InputError: `joint_values` names an unknown, fixed or mimic joint.
        UsageError: the result kept no model (a result of `lint_files` or the cache).
    """
    from robotdesc.view.scene import DEFAULT_MAX_FACES, build_scene

    started = time.perf_counter()
    robot = result.robot
    if robot is None:
        raise UsageError(f"{result.target}: a report needs a lint result that kept its model "
                         "(robotdesc.lint_file keeps it)")
    notes: list[str] = []
    # the one package lookup of the report: the 3D view and the inertia table share it
    find_package = package_lookup(result.target, tuple(package_paths), tuple(package_map))
    scene = build_scene(robot, joint_values, meshes=MeshLocator(robot, find_package),
                        max_faces=max_faces or DEFAULT_MAX_FACES) if view else None
    settings = mesh_settings or MeshSettings()
    rows = _inertia_rows(robot, result.target, settings, find_package, result_verdict(result))
    if scene is not None and scene.problems:
        notes.append(f"{len(scene.problems)} geometries could not be shown in the 3D view")
    collision = None
    if collision_method:
        from robotdesc.collision.generate import generate_collision

        collision = generate_collision(robot, collision_method, options=collision_options,
                                       package_paths=tuple(package_paths),
                                       package_map=tuple(package_map), jobs=jobs)
    return ReportData(result, robot, scene, rows, collision, tuple(notes),
                      time.perf_counter() - started)


def _inertia_rows(robot: Robot, target: str, settings: MeshSettings,
                  find_package: PackageLookup,
                  verdict: Mapping[str, tuple[str, ...]]) -> tuple[InertiaRow, ...]:
    """The inertia table, each row marked with lint's suppressed findings on its link."""
    meshes = MeshContext.for_file(robot, target, settings, find_package=find_package)
    return tuple(mark_rows(inertia_table(robot, meshes), verdict))
