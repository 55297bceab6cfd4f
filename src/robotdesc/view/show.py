"""`show()`: a robot's 3D view for notebooks and for files.

`show("robot.urdf.xacro")` lints the description (to highlight the links with findings),
builds the scene at a configuration and returns a `View`: Jupyter displays it inline (an
iframe holding the self-contained page), `.save(path)` writes the page.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from robotdesc.diagnostics import Diagnostic
from robotdesc.errors import RobotdescError, UsageError
from robotdesc.expansion import ExpandOptions, expand_file
from robotdesc.linting.driver import lint_file
from robotdesc.model.elements import Robot
from robotdesc.model.parse import parse_urdf
from robotdesc.output import write_output
from robotdesc.view.findings import findings_by_link
from robotdesc.view.html import view_page
from robotdesc.view.preview import preview_iframe

SHOW_OPTIONS = ("visual", "collision", "inertia", "findings")


@dataclass(frozen=True, eq=False)
class View:
    """A rendered view: the scene document and the page built from it.

    Attributes:
        document: the scene document the viewer reads (see robotdesc.view.encode).
        height: CSS height of the inline (notebook) display.
    """

    document: dict[str, Any] = field(repr=False)
    height: str = "560px"

    def html(self) -> str:
        """The complete, self-contained HTML page."""
        return view_page(self.document)

    def save(self, path: str | os.PathLike[str]) -> str:
        """Write the page to `path` (UTF-8); returns the path written."""
        target = os.fspath(path)
        write_output(target, self.html().encode("utf-8"))
        return target

    def to_dict(self) -> dict[str, Any]:
        """The scene document (JSON-ready; arrays as base64 strings)."""
        return self.document

    def __repr__(self) -> str:
        doc = self.document
        flagged = sum(1 for link in doc["links"] if link["findings"])
        return (f"<View {doc['robot']!r}: {len(doc['links'])} links, "
                f"{len(doc['instances'])} shapes, {flagged} links with findings>")

    def _repr_html_(self) -> str:
        """An iframe (scripts run in the frame only) holding a preview of the page: meshes
        reduced, the page compressed (see robotdesc.view.preview); `.save()` writes the
        full page."""
        return preview_iframe(self.document, self.height)


def show(target: Any, joint_values: Mapping[str, float] | None = None, *,
         args: Mapping[str, str] | None = None, package_paths: Sequence[str] = (),
         package_map: Sequence[tuple[str, str]] = (),
         findings: Iterable[Diagnostic] | None = None, lint: bool = True,
         visible: Sequence[str] = ("visual", "findings"), max_faces: int | None = None,
         title: str | None = None) -> View:
    """Build the 3D view of a robot.

    Args:
        target: a description file (xacro or URDF), a `Robot` (`robotdesc.load`) or a
            `LintResult` (`robotdesc.lint`).
        joint_values: joint name -> value (rad or m); others at 0 (or their nearest limit).
        args: xacro arguments, when `target` is a file.
        package_paths: folders searched for ROS packages first.
        package_map: (package name, folder) pairs for `package://` meshes.
        findings: diagnostics to highlight (default: those of `target` when it is a
            `LintResult`, or of linting it when it is a file and `lint` is true).
        lint: lint a file `target` to find the links with findings.
        visible: what is shown when the page opens: any of "visual", "collision",
            "inertia" (equivalent inertia boxes), "findings" (highlighting).
        max_faces: display budget per mesh file (default: scene.DEFAULT_MAX_FACES).
        title: the heading (default: the robot's name).

    Raises:
        robotdesc.errors.InputError: the file could not be read, or `joint_values` names an
            unknown, fixed or mimic joint.
    """
    from robotdesc.view.encode import scene_document
    from robotdesc.view.scene import DEFAULT_MAX_FACES, build_scene

    unknown = [name for name in visible if name not in SHOW_OPTIONS]
    if unknown:
        raise UsageError(f"unknown view option '{unknown[0]}' (choose from "
                         f"{', '.join(SHOW_OPTIONS)})")
    robot, diagnostics = _robot_and_findings(target, args, package_paths, lint)
    if findings is not None:
        diagnostics = tuple(findings)
    scene = build_scene(robot, joint_values, package_paths=tuple(package_paths),
                        package_map=tuple(package_map), max_faces=max_faces or DEFAULT_MAX_FACES)
    per_link, _ = findings_by_link(robot, diagnostics)
    document = scene_document(scene, per_link, title)
    document["show"] = {name: name in visible for name in SHOW_OPTIONS}
    return View(document)


def _robot_and_findings(target: Any, args: Mapping[str, str] | None,
                        package_paths: Sequence[str], lint: bool
                        ) -> tuple[Robot, tuple[Diagnostic, ...]]:
    if isinstance(target, Robot):
        return target, ()
    robot = getattr(target, "robot", None)
    if isinstance(robot, Robot):  # a LintResult
        return robot, tuple(getattr(target, "diagnostics", ()))
    if isinstance(target, (str, os.PathLike)):
        path = os.fspath(target)
        options = ExpandOptions(package_paths=tuple(package_paths))
        if lint:
            result = lint_file(path, args=args, expand_options=options)
            if result.robot is None:
                raise RobotdescError(f"{path}: the lint kept no model")
            return result.robot, tuple(result.diagnostics)
        expanded = expand_file(path, dict(args or {}), options=options)
        return parse_urdf(expanded.xml, expanded.source, expanded.files), ()
    raise TypeError(f"show() takes a file path, a Robot or a LintResult, not "
                    f"{type(target).__name__}")
