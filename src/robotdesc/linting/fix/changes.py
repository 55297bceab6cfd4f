"""What a finding's fix changes in the expanded description: attribute values of expanded
elements. Where the change goes in the xacro source is plan.py's job.

Each fixer reads a `Diagnostic` (its `fix` text when the rule gives one, else the expanded
element it names) and returns the `AttributeChange`s, or a `NotApplicable` saying why not.
"""

from __future__ import annotations

import math
import os
import re
import urllib.parse
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

from lxml import etree

from robotdesc.diagnostics import Diagnostic
from robotdesc.source import PROVENANCE_ATTR, Provenance, Span, decode_provenance

_ELEMENT = re.compile(r"^(link|joint):([^/]+)(?:/(\w+)(?:\[(\d+)\])?)?$")
_INERTIA_ATTRIBUTES = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
_DEFAULTS = {("origin", "xyz"): "0 0 0", ("origin", "rpy"): "0 0 0"}


@dataclass(frozen=True)
class AttributeChange:
    """Set `attribute` of one expanded element to `value` (adding it when absent)."""

    element: etree._Element  # of the expanded document
    attribute: str
    value: str


@dataclass(frozen=True)
class NotApplicable:
    """Why a finding's fix cannot be written back."""

    reason: str


#: What a fixer returns: the changes, or why there are none.
Changes = list[AttributeChange] | NotApplicable


class CaseHelper(Protocol):
    """M102's helper (`robotdesc.linting.fix.run.MeshCase`): the file on disk that a
    case-mismatched mesh reference names."""

    def case_candidate(self, element: str) -> str | None:
        """The path of the file on disk whose name differs from the reference's only in
        case, for the `<mesh>` of diagnostic element `element`; None when there is none."""
        ...


class ExpandedIndex:
    """The expanded document with each element's provenance, by link and joint name."""

    def __init__(self, xml: bytes, source: str, files: tuple[str, ...]) -> None:
        self.root = etree.fromstring(xml, etree.XMLParser(remove_comments=False,
                                                          resolve_entities=False))
        self.source, self.files = source, files
        self.links = {e.get("name"): e for e in self.root.iterchildren("link")}
        self.joints = {e.get("name"): e for e in self.root.iterchildren("joint")}
        self._where: dict[etree._Element, Provenance] = {}
        self.by_span: dict[tuple[str, int, str], list[etree._Element]] = {}
        for element in self.root.iter(etree.Element):
            span = self.where(element).span
            self.by_span.setdefault((span.path, span.line, _local(element.tag)), []).append(
                element)

    def where(self, element: etree._Element) -> Provenance:
        """The element's own provenance (not an ancestor's)."""
        found = self._where.get(element)
        if found is None:
            value = element.get(PROVENANCE_ATTR)
            if value and self.files:
                found = decode_provenance(value, self.files)
            else:
                found = Provenance(Span(self.source, element.sourceline or 0))
            self._where[element] = found
        return found

    def element(self, name: str) -> etree._Element | None:
        """The expanded element a diagnostic's element name points to, or None."""
        match = _ELEMENT.match(name or "")
        if match is None:
            return None
        kind, owner, child, index = match.groups()
        parent = (self.links if kind == "link" else self.joints).get(owner)
        if parent is None or child is None:
            return parent
        found = [c for c in parent.iterchildren(child)]
        position = int(index) if index is not None else 0
        return found[position] if position < len(found) else None


def _local(tag: object) -> str:
    return tag.rpartition("}")[2] if isinstance(tag, str) else ""


def _geometry_mesh(element: etree._Element | None) -> etree._Element | None:
    """The `<mesh>` of a visual or collision element, or None."""
    if element is None:
        return None
    return next(iter(element.iterfind("geometry/mesh")), None)


def _numbers(text: str | None) -> list[float] | None:
    try:
        return [float(v) for v in (text or "").split()]
    except ValueError:
        return None


def _same(a: str | None, b: str) -> bool:
    left, right = _numbers(a), _numbers(b)
    if left is None or right is None or len(left) != len(right):
        return a == b
    return all(math.isclose(x, y, rel_tol=1e-9, abs_tol=1e-15) for x, y in zip(left, right))


# --- fixers -------------------------------------------------------------------------------


def inertial_changes(diagnostic: Diagnostic, index: ExpandedIndex, _: CaseHelper | None
                     ) -> Changes:
    """The attribute changes that turn the declared `<inertial>` into the suggested block."""
    try:
        block = etree.fromstring(diagnostic.fix or "")
    except etree.XMLSyntaxError:
        return NotApplicable("the suggested <inertial> is not XML")
    declared = index.element(diagnostic.element)
    if declared is None or _local(declared.tag) != "inertial":
        return NotApplicable("the declared <inertial> was not found")
    changes: list[AttributeChange] = []
    for wanted in block.iterchildren(etree.Element):
        tag = _local(wanted.tag)
        have = next(iter(declared.iterchildren(tag)), None)
        names = _INERTIA_ATTRIBUTES if tag == "inertia" else tuple(wanted.attrib)
        for name in names:
            value = wanted.get(name, "0")
            if have is None:
                if not _same(_DEFAULTS.get((tag, name), ""), value):
                    return NotApplicable(f"the declared <inertial> has no <{tag}> to edit")
                continue
            current = have.get(name, _DEFAULTS.get((tag, name)))
            if not _same(current, value):
                changes.append(AttributeChange(have, name, value))
    return changes


def axis_changes(diagnostic: Diagnostic, index: ExpandedIndex, _: CaseHelper | None) -> Changes:
    """J107: the axis at unit length (the rule's fix text)."""
    joint = index.element(diagnostic.element)
    axis = next(iter(joint.iterchildren("axis")), None) if joint is not None else None
    match = re.search(r'xyz="([^"]*)"', diagnostic.fix or "")
    if axis is None or match is None:
        return NotApplicable("the joint's <axis> was not found")
    return [AttributeChange(axis, "xyz", match.group(1))]


def limit_changes(diagnostic: Diagnostic, index: ExpandedIndex, _: CaseHelper | None
                  ) -> Changes:
    """J103: lower and upper swapped."""
    joint = index.element(diagnostic.element)
    limit = next(iter(joint.iterchildren("limit")), None) if joint is not None else None
    if limit is None or limit.get("lower") is None or limit.get("upper") is None:
        return NotApplicable("the joint's <limit> does not give both lower and upper")
    return [AttributeChange(limit, "lower", limit.get("upper")),
            AttributeChange(limit, "upper", limit.get("lower"))]


def scale_changes(diagnostic: Diagnostic, index: ExpandedIndex, _: CaseHelper | None
                  ) -> Changes:
    """M108: the mesh scaled by 0.001."""
    mesh = _geometry_mesh(index.element(diagnostic.element))
    if mesh is None:
        return NotApplicable("the <mesh> was not found")
    scale = _numbers(mesh.get("scale", "1 1 1"))
    if scale is None or len(scale) != 3:
        return NotApplicable(f"the scale '{mesh.get('scale')}' is not three numbers")
    return [AttributeChange(mesh, "scale", " ".join(f"{v * 0.001:g}" for v in scale))]


def case_changes(diagnostic: Diagnostic, index: ExpandedIndex, helper: CaseHelper | None
                 ) -> Changes:
    """M102: the file name spelt as the file on disk."""
    mesh = _geometry_mesh(index.element(diagnostic.element))
    candidate = helper.case_candidate(diagnostic.element) if helper is not None else None
    if mesh is None or not candidate:
        return NotApplicable("the file with the right case was not found")
    parts = mesh.get("filename", "").split("/")
    actual = os.path.normpath(candidate).split(os.sep)
    if len(actual) < 1:
        return NotApplicable("the file with the right case was not found")
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
        return NotApplicable("the <mesh> was not found")
    filename = mesh.get("filename", "")
    path = filename
    if filename.lower().startswith("file://"):
        path = urllib.parse.unquote(urllib.parse.urlparse(filename).path)
    if not os.path.isabs(path):
        return NotApplicable(f"'{filename}' is not an absolute path")
    found = enclosing_package(path)
    if found is None:
        return NotApplicable(f"'{path}' is in no ROS package (no package.xml above it)")
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
    "J103": limit_changes, "J107": axis_changes, "M102": case_changes,
    "M108": scale_changes, "P101": package_changes, "P102": package_changes,
}


def fixer_for(diagnostic: Diagnostic) -> Fixer | None:
    """The fixer of a diagnostic: its rule's, or the inertial one for an `<inertial>` fix."""
    found = FIXERS.get(diagnostic.code)
    if found is None and (diagnostic.fix or "").lstrip().startswith("<inertial"):
        return inertial_changes
    return found
