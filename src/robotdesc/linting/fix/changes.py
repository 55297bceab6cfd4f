"""What a finding's fix changes in the expanded description: attribute values of expanded
elements. Where the change goes in the xacro source is robotdesc.edit.locate's job.

Each fixer reads a `Diagnostic` (its `fix` text when the rule gives one, else the expanded
element it names) and returns the `AttributeChange`s, or a `Refused` saying why not.
"""

from __future__ import annotations

import os
import urllib.parse
from collections.abc import Callable
from typing import Protocol

from lxml import etree

from robotdesc.diagnostics import Diagnostic
from robotdesc.edit.index import AttributeChange, Changes, ExpandedIndex, Refused
from robotdesc.edit.values import numbers as _numbers
from robotdesc.inertia.patch import inertial_changes as block_changes


class CaseHelper(Protocol):
    """M102's helper (`robotdesc.linting.fix.run.MeshCase`): the file on disk that a
    case-mismatched mesh reference names."""

    def case_candidate(self, element: str) -> str | None:
        """The path of the file on disk whose name differs from the reference's only in
        case, for the `<mesh>` of diagnostic element `element`; None when there is none."""
        ...


def _geometry_mesh(element: etree._Element | None) -> etree._Element | None:
    """The `<mesh>` of a visual or collision element, or None."""
    if element is None:
        return None
    return next(iter(element.iterfind("geometry/mesh")), None)


# --- fixers -------------------------------------------------------------------------------


def inertial_changes(diagnostic: Diagnostic, index: ExpandedIndex, _: CaseHelper | None
                     ) -> Changes:
    """The attribute changes that turn the declared `<inertial>` into the suggested block
    (the same as `inertia --write`'s, robotdesc.inertia.patch)."""
    return block_changes(diagnostic.fix or "", index.element(diagnostic.element))


def requested_changes(diagnostic: Diagnostic, index: ExpandedIndex, _: CaseHelper | None
                      ) -> Changes:
    """The changes the rule asked for with its finding (`Finding.changes`)."""
    found: list[AttributeChange] = []
    for change in diagnostic.changes:
        element = index.element(change.element)
        if element is None:
            return Refused(f"{change.element} is not in the expanded description")
        found.append(AttributeChange(element, change.attribute, change.value,
                                     tolerance=change.tolerance))
    return found


def scale_changes(diagnostic: Diagnostic, index: ExpandedIndex, _: CaseHelper | None
                  ) -> Changes:
    """M108: the mesh scaled by 0.001."""
    mesh = _geometry_mesh(index.element(diagnostic.element))
    if mesh is None:
        return Refused("the <mesh> was not found")
    scale = _numbers(mesh.get("scale", "1 1 1"))
    if scale is None or len(scale) != 3:
        return Refused(f"the scale '{mesh.get('scale')}' is not three numbers")
    return [AttributeChange(mesh, "scale", " ".join(f"{v * 0.001:g}" for v in scale))]


def case_changes(diagnostic: Diagnostic, index: ExpandedIndex, helper: CaseHelper | None
                 ) -> Changes:
    """M102: the file name spelt as the file on disk."""
    mesh = _geometry_mesh(index.element(diagnostic.element))
    candidate = helper.case_candidate(diagnostic.element) if helper is not None else None
    if mesh is None or not candidate:
        return Refused("the file with the right case was not found")
    parts = mesh.get("filename", "").split("/")
    actual = os.path.normpath(candidate).split(os.sep)
    if len(actual) < 1:
        return Refused("the file with the right case was not found")
    fixed = list(parts)
    for offset in range(1, min(len(parts), len(actual)) + 1):
        if parts[-offset].lower() != actual[-offset].lower():
            break
        fixed[-offset] = actual[-offset]
    return [AttributeChange(mesh, "filename", "/".join(fixed))]


def package_changes(diagnostic: Diagnostic, index: ExpandedIndex, _: CaseHelper | None
                    ) -> Changes:
    """P101/P102: an absolute path or file:// URI as package://PACKAGE/PATH."""
    mesh = _geometry_mesh(index.element(diagnostic.element))
    if mesh is None:
        return Refused("the <mesh> was not found")
    filename = mesh.get("filename", "")
    path = filename
    if filename.lower().startswith("file://"):
        path = urllib.parse.unquote(urllib.parse.urlparse(filename).path)
    if not os.path.isabs(path):
        return Refused(f"'{filename}' is not an absolute path")
    found = enclosing_package(path)
    if found is None:
        return Refused(f"'{path}' is in no ROS package (no package.xml above it)")
    name, root = found
    relative = os.path.relpath(os.path.normpath(path), root).replace(os.sep, "/")
    return [AttributeChange(mesh, "filename", f"package://{name}/{relative}")]


def enclosing_package(path: str) -> tuple[str, str] | None:
    """(name, folder) of the nearest folder above `path` holding a package.xml."""
    folder = os.path.dirname(os.path.normpath(path))
    while True:
        manifest = os.path.join(folder, "package.xml")
        if os.path.isfile(manifest):
            try:
                name = etree.parse(manifest).findtext("name")
            except (OSError, etree.XMLSyntaxError):
                name = None
            return (name.strip(), folder) if name and name.strip() else None
        parent = os.path.dirname(folder)
        if parent == folder:
            return None
        folder = parent


#: A fixer: the diagnostic, the expanded document, M102's helper (None: not known).
Fixer = Callable[[Diagnostic, ExpandedIndex, CaseHelper | None], Changes]

FIXERS: dict[str, Fixer] = {
    "M102": case_changes,
    "M108": scale_changes, "P101": package_changes, "P102": package_changes,
}


def fixer_for(diagnostic: Diagnostic) -> Fixer | None:
    """The fixer of a diagnostic: the changes its rule asked for, else its rule's fixer
    here, or the inertial one for an `<inertial>` fix."""
    if diagnostic.changes:
        return requested_changes
    found = FIXERS.get(diagnostic.code)
    if found is None and (diagnostic.fix or "").lstrip().startswith("<inertial"):
        return inertial_changes
    return found
