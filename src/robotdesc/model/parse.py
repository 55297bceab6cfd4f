"""Strict URDF parse: bytes -> `Robot`, every element tagged with its provenance.

The XML is parsed without recovery, without entity expansion, DTD loading or network access;
a document that declares a DOCTYPE is refused. Numbers that do not parse become None (or the
URDF default) and a `ValueIssue` on the robot, so that one bad value is a finding, not a crash.
Unknown elements are ignored, as URDF consumers do.
"""

from __future__ import annotations

import logging
import math
import os
import re
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TypeVar, cast

from lxml import etree

from robotdesc.errors import InputError, XmlSyntaxError
from robotdesc.model.elements import (
    Actuator,
    Box,
    Calibration,
    Capsule,
    Collision,
    Cylinder,
    Dynamics,
    GazeboBlock,
    Geometry,
    Inertia,
    Inertial,
    Joint,
    JointLimit,
    Link,
    Material,
    MeshRef,
    Mimic,
    Pose,
    Robot,
    SafetyController,
    Sphere,
    Transmission,
    TransmissionJoint,
    ValueIssue,
    Vec3,
    Visual,
)
from robotdesc.model.numbers import DEFAULT_LIMITS, NumberLimits, check_number, check_vector
from robotdesc.source import (
    PASSED_SEPARATOR,
    PROVENANCE_ATTR,
    Provenance,
    Span,
    decode_passed,
    decode_provenance,
    strip_provenance,  # noqa: F401  (re-exported: its old home)
)
from robotdesc.xml_input import XmlOptions, parse_xml, start_tag_positions

log = logging.getLogger(__name__)

_Read = TypeVar("_Read")

_ZERO: Vec3 = (0.0, 0.0, 0.0)
_DESCRIPTION = XmlOptions(what="robot description")


def parse_urdf(data: bytes, path: str, files: tuple[str, ...] = ()) -> Robot:
    """Parse a URDF document strictly into a `Robot`.

    Args:
        data: the document (UTF-8 or with an XML encoding declaration).
        path: the file it came from, used in errors and (for plain URDF) in provenance.
        files: the expansion's file table; when given, elements carry the private provenance
            attribute (`robotdesc.source.PROVENANCE_ATTR`) indexing it.

    Returns:
        The robot, with unreadable values recorded in `Robot.value_issues`.

    Raises:
        XmlSyntaxError: the XML is malformed or declares a DOCTYPE.
        InputError: the root element is not `<robot>`.
    """
    if isinstance(data, str):
        data = data.encode("utf-8")
    try:
        root = parse_xml(data, path, _DESCRIPTION)
    except XmlSyntaxError as error:
        if not files or error.span is None or not error.span.line:
            raise
        # a position in the expanded document is no position in the xacro source
        raise XmlSyntaxError(f"{error.message} (in the document xacro expanded this file to, "
                             f"line {error.span.line})", Span(path)) from None
    positions = {} if files else start_tag_positions(data, root)
    if root.tag != "robot":
        line, col = positions.get(root, (root.sourceline or 0, 0))
        raise InputError(f"the root element is <{_tag(root)}>, expected <robot>",
                         Span(path, line, col))
    return _RobotReader(path, files, positions).robot(root)


def _tag(element: etree._Element) -> str:
    tag = element.tag
    return tag.rpartition("}")[2] if isinstance(tag, str) else str(tag)


def _children(element: etree._Element, tag: str) -> list[etree._Element]:
    return [child for child in element if child.tag == tag]


def _first(element: etree._Element, tag: str) -> etree._Element | None:
    for child in element:
        if child.tag == tag:
            return child
    return None


def _firsts(element: etree._Element) -> dict[str, etree._Element]:
    """The first child of each tag (URDF consumers read the first and ignore repeats)."""
    index: dict[str, etree._Element] = {}
    for child in element:
        if child.tag not in index:
            index[child.tag] = child
    return index


class _RobotReader:
    """Walks the tree once; collects value issues; caches decoded provenance."""

    def __init__(self, path: str, files: tuple[str, ...],
                 positions: dict[etree._Element, tuple[int, int]] | None = None,
                 limits: NumberLimits = DEFAULT_LIMITS) -> None:
        self.path = path
        self.files = files
        self.positions = positions or {}
        self.limits = limits
        self.issues: list[ValueIssue] = []
        self._decoded: dict[tuple[str, str], Provenance] = {}
        shared = _decodings(files)
        self._columns = shared.columns
        self._spans = shared.spans
        self._chains = shared.chains
        self._earlier = shared.decoded
        self._elements = shared.elements
        #: the source files whose state the provenance decoded since the last reset (the
        #: files a memoized element depends on: see `_memoized`)
        self._consulted: set[str] = set()

    # -- provenance -------------------------------------------------------------------------

    def where(self, element: etree._Element, inherited: Provenance | None) -> Provenance:
        """The element's provenance: its own attribute, else the nearest ancestor's."""
        if self.files:
            value = element.get(PROVENANCE_ATTR)
            if value is not None:
                key = (value, element.tag)
                found = self._decoded.get(key)
                if found is None:
                    return self._earlier_decoding(key) or self._decode(value, element,
                                                                       inherited)
                self._consulted.add(found.span.path)
                return found
            if inherited is not None:
                return inherited
        line, col = self.positions.get(element, (element.sourceline or 0, 0))
        return Provenance(Span(self.path, line, col))

    def _decode(self, value: str, element: etree._Element,
                inherited: Provenance | None) -> Provenance:
        """Decode one attribute value (`robotdesc.source.decode_provenance`), with caches.

        The elements of one macro body share their call chain, so the chain and each own
        position are decoded once and reused.
        """
        head, _, passed_part = value.partition(PASSED_SEPARATOR)
        own, _, calls = head.partition(";")
        try:
            span = self._spans.get(own)
            if span is None:
                span = self._spans[own] = decode_provenance(own, self.files).span
            chain = self._chains.get(calls)
            if chain is None:
                if calls:
                    calling = decode_provenance(calls, self.files)
                    chain = (calling.span, *calling.macro_stack)
                else:
                    chain = ()
                self._chains[calls] = chain
            passed = decode_passed(passed_part, self.files) if passed_part else ()
        except (ValueError, IndexError):
            log.warning("ignoring malformed provenance %r on <%s>", value, _tag(element))
            return inherited or Provenance(Span(self.path, element.sourceline or 0))
        col = self._columns.column(span, _tag(element))
        found = self._decoded[(value, element.tag)] = Provenance(
            Span(span.path, span.line, col) if col else span, chain, passed)
        self._earlier[(value, element.tag)] = (found, self._columns.state(span.path))
        self._consulted.add(span.path)
        return found

    def _earlier_decoding(self, key: tuple[str, str]) -> Provenance | None:
        """The provenance an earlier parse with this file table decoded for the same
        attribute and tag, when the file its column was read from is unchanged."""
        earlier = self._earlier.get(key)
        if earlier is None or self._columns.state(earlier[0].span.path) != earlier[1]:
            return None
        self._decoded[key] = earlier[0]
        self._consulted.add(earlier[0].span.path)
        return earlier[0]

    def _memoized(self, element: etree._Element, parent: Provenance,
                  read: Callable[[etree._Element, Provenance], _Read]) -> _Read:
        """`read(element, parent)` of a top-level element, or what an earlier parse with this
        file table read from the same bytes under the same parent provenance, when the files
        its provenance was decoded from (their columns) are unchanged: the variants of one
        description and an editor's saves share most elements. Its value issues are
        recorded again."""
        if not self.files:
            return read(element, parent)
        key = (etree.tostring(element, with_tail=False), parent)
        earlier = self._elements.get(key)
        if earlier is not None and all(self._columns.state(path) == state
                                       for path, state in earlier.files):
            self.issues.extend(earlier.issues)
            return cast("_Read", earlier.value)
        issues_before, consulted = len(self.issues), self._consulted
        self._consulted = set()
        value = read(element, parent)
        files = tuple((path, self._columns.state(path)) for path in sorted(self._consulted))
        consulted.update(self._consulted)
        self._consulted = consulted
        if len(self._elements) >= _MEMOIZED_ELEMENTS:
            self._elements.clear()
        self._elements[key] = _Memoized(value, tuple(self.issues[issues_before:]), files)
        return value

    # -- values -----------------------------------------------------------------------------

    def issue(self, message: str, where: Provenance, element: str) -> None:
        self.issues.append(ValueIssue(message, where, element))

    def number(self, text: str | None, what: str, where: Provenance, owner: str,
               default: float | None = None, required: bool = False,
               bound: float | None = None) -> float | None:
        """Read one number; a missing required one, an unreadable one or one that is not
        finite or beyond `bound` in magnitude (default: the limit of "other") is an issue."""
        if text is None:
            if required:
                self.issue(f"{what} is missing (required)", where, owner)
            return default
        try:
            value = float(text)
        except ValueError:
            value = None
        if value is None or math.isnan(value) or "_" in text:
            self.issue(f"{what}=\"{_clip(text)}\" is not a number", where, owner)
            return default
        problem = check_number(value, self.limits.other if bound is None else bound,
                               self.limits.tiny)
        if problem:
            self.issue(f"{what}=\"{_clip(text)}\" {problem}", where, owner)
            return default
        return value + 0.0  # -0 is 0 (numpy's samplers refuse uniform(0.0, -0.0))

    def vector(self, text: str | None, size: int, what: str, where: Provenance, owner: str,
               default: tuple[float, ...] | None = None, required: bool = False,
               bound: float | None = None) -> tuple[float, ...] | None:
        """Read `size` whitespace-separated numbers (each finite and within `bound`)."""
        if text is None:
            if required:
                self.issue(f"{what} is missing (required)", where, owner)
            return default
        try:
            values = tuple(map(float, text.split()))
        except ValueError:
            values = ()
        if (len(values) != size or "_" in text
                or (("a" in text or "A" in text) and any(map(math.isnan, values)))):
            self.issue(f"{what}=\"{_clip(text)}\" is not {size} numbers", where, owner)
            return default
        problem = check_vector(values, self.limits.other if bound is None else bound,
                               self.limits.tiny)
        if problem:
            reason = problem.replace("is", "has a value that is", 1)
            self.issue(f"{what}=\"{_clip(text)}\" {reason}",
                       where, owner)
            return default
        return tuple(value + 0.0 for value in values)

    # -- elements ---------------------------------------------------------------------------


    def vector3(self, text: str | None, what: str, where: Provenance, owner: str,
                default: Vec3 | None = None, required: bool = False,
                bound: float | None = None) -> Vec3 | None:
        """`vector` of three numbers, typed as such."""
        found = self.vector(text, 3, what, where, owner, default, required, bound)
        return (found[0], found[1], found[2]) if found is not None else None
    def robot(self, root: etree._Element) -> Robot:
        where = self.where(root, None)
        name = root.get("name")
        if not name:
            self.issue("<robot> has no name (required)", where, "robot")
        links: list[Link] = []
        joints: list[Joint] = []
        materials: list[Material] = []
        transmissions: list[Transmission] = []
        gazebo: list[GazeboBlock] = []
        for child in root:
            tag = child.tag
            if tag == "link":
                links.append(self._memoized(child, where, self.link))
            elif tag == "joint":
                joints.append(self._memoized(child, where, self.joint))
            elif tag == "material":
                materials.append(self._memoized(child, where, self._top_material))
            elif tag == "transmission":
                transmissions.append(self._memoized(child, where, self.transmission))
            elif tag == "gazebo":
                gazebo.append(self._memoized(child, where, self.gazebo))
        return Robot(name=name or "", links=tuple(links), joints=tuple(joints),
                     materials=tuple(materials), transmissions=tuple(transmissions),
                     gazebo=tuple(gazebo), value_issues=tuple(self.issues), source=self.path,
                     where=where)

    def _top_material(self, element: etree._Element, parent: Provenance) -> Material:
        return self.material(element, parent, "material")

    def pose(self, element: etree._Element | None, parent: Provenance, owner: str) -> Pose:
        if element is None:
            return Pose()
        where = self.where(element, parent)
        xyz = self.vector3(element.get("xyz"), "<origin> xyz", where, owner, _ZERO,
                           bound=self.limits.length)
        rpy = self.vector3(element.get("rpy"), "<origin> rpy", where, owner, _ZERO,
                           bound=self.limits.angle)
        return Pose(xyz or _ZERO, rpy or _ZERO, where)

    def link(self, element: etree._Element, parent: Provenance) -> Link:
        where = self.where(element, parent)
        name = element.get("name") or ""
        owner = f"link:{name}"
        if not name:
            self.issue("<link> has no name (required)", where, owner)
        inertial_element = None
        visual_elements: list[etree._Element] = []
        collision_elements: list[etree._Element] = []
        for child in element:
            tag = child.tag
            if tag == "visual":
                visual_elements.append(child)
            elif tag == "collision":
                collision_elements.append(child)
            elif tag == "inertial" and inertial_element is None:
                inertial_element = child
        inertial = (self.inertial(inertial_element, where, owner)
                    if inertial_element is not None else None)
        visuals = tuple(self.visual(v, where, f"{owner}/visual[{i}]")
                        for i, v in enumerate(visual_elements))
        collisions = tuple(self.collision(c, where, f"{owner}/collision[{i}]")
                           for i, c in enumerate(collision_elements))
        return Link(name, inertial, visuals, collisions, where)

    def inertial(self, element: etree._Element, parent: Provenance, owner: str) -> Inertial:
        where = self.where(element, parent)
        kids = _firsts(element)
        origin = self.pose(kids.get("origin"), where, owner)
        mass_element = kids.get("mass")
        mass = None
        passed = list(where.passed)
        passed += [value for value in (origin.where.passed if origin.where else ())
                   if value not in passed]
        if mass_element is None:
            self.issue("<inertial> has no <mass> (required)", where, owner)
        else:
            mass_where = self.where(mass_element, where)
            passed += [value for value in mass_where.passed if value not in passed]
            mass = self.number(mass_element.get("value"), "<mass> value", mass_where, owner,
                               required=True, bound=self.limits.mass)
        inertia_element = kids.get("inertia")
        inertia = None
        if inertia_element is None:
            self.issue("<inertial> has no <inertia> (required)", where, owner)
        else:
            inertia = self.inertia(inertia_element, where, owner)
            if inertia is not None and inertia.where is not None:
                passed += [value for value in inertia.where.passed if value not in passed]
        if len(passed) > len(where.passed):
            where = replace(where, passed=tuple(passed))
        return Inertial(origin, mass, inertia, where)

    def inertia(self, element: etree._Element, parent: Provenance, owner: str) -> Inertia | None:
        where = self.where(element, parent)
        values = [self.number(element.get(key), f"<inertia> {key}", where, owner, required=True,
                              bound=self.limits.inertia)
                  for key in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")]
        ixx, ixy, ixz, iyy, iyz, izz = values
        if ixx is None or ixy is None or ixz is None or iyy is None or iyz is None \
                or izz is None:
            return None
        return Inertia(ixx, ixy, ixz, iyy, iyz, izz, where=where)

    def visual(self, element: etree._Element, parent: Provenance, owner: str) -> Visual:
        where = self.where(element, parent)
        kids = _firsts(element)
        origin = self.pose(kids.get("origin"), where, owner)
        geometry = self.geometry(kids.get("geometry"), where, owner)
        material_element = kids.get("material")
        material = (self.material(material_element, where, owner)
                    if material_element is not None else None)
        return Visual(element.get("name"), origin, geometry, material, where)

    def collision(self, element: etree._Element, parent: Provenance, owner: str) -> Collision:
        where = self.where(element, parent)
        kids = _firsts(element)
        origin = self.pose(kids.get("origin"), where, owner)
        geometry = self.geometry(kids.get("geometry"), where, owner)
        return Collision(element.get("name"), origin, geometry, where)

    def geometry(self, element: etree._Element | None, parent: Provenance,
                 owner: str) -> Geometry | None:
        if element is None:
            self.issue("<geometry> is missing (required)", parent, owner)
            return None
        where = self.where(element, parent)
        shape = next((child for child in element if isinstance(child.tag, str)), None)
        if shape is None:
            self.issue("<geometry> has no shape (box, cylinder, sphere or mesh)", where, owner)
            return None
        reader = _SHAPES.get(shape.tag)
        if reader is None:
            self.issue(f"<geometry> has an unknown shape <{_tag(shape)}>", where, owner)
            return None
        return reader(self, shape, self.where(shape, where), owner)

    def material(self, element: etree._Element, parent: Provenance, owner: str) -> Material:
        where = self.where(element, parent)
        name = element.get("name") or ""
        if owner == "material":
            owner = f"material:{name}"
            if not name:
                self.issue("<material> has no name (required)", where, owner)
        color: tuple[float, float, float, float] | None = None
        color_element = _first(element, "color")
        if color_element is not None:
            rgba = self.vector(color_element.get("rgba"), 4, "<color> rgba",
                               self.where(color_element, where), owner, required=True)
            color = (rgba[0], rgba[1], rgba[2], rgba[3]) if rgba is not None else None
        texture_element = _first(element, "texture")
        texture = texture_element.get("filename") if texture_element is not None else None
        return Material(name, color, texture, where)

    def joint(self, element: etree._Element, parent: Provenance) -> Joint:
        where = self.where(element, parent)
        kids = _firsts(element)
        name = element.get("name") or ""
        owner = f"joint:{name}"
        if not name:
            self.issue("<joint> has no name (required)", where, owner)
        origin = self.pose(kids.get("origin"), where, owner)
        axis, axis_where = None, None
        axis_element = kids.get("axis")
        if axis_element is not None:
            axis_where = self.where(axis_element, where)
            axis = self.vector3(axis_element.get("xyz"), "<axis> xyz", axis_where, owner,
                                (1.0, 0.0, 0.0), bound=self.limits.length)
        return Joint(
            name=name, type=element.get("type") or "",
            parent=self.link_reference(kids.get("parent")),
            child=self.link_reference(kids.get("child")),
            origin=origin, axis=axis,
            limit=self.optional(kids, "limit", where, owner, self.limit),
            dynamics=self.optional(kids, "dynamics", where, owner, self.dynamics),
            mimic=self.optional(kids, "mimic", where, owner, self.mimic),
            safety_controller=self.optional(kids, "safety_controller", where, owner,
                                            self.safety_controller),
            calibration=self.optional(kids, "calibration", where, owner, self.calibration),
            where=where, axis_where=axis_where)

    @staticmethod
    def link_reference(element: etree._Element | None) -> str:
        return (element.get("link") or "") if element is not None else ""

    def optional(self, kids: dict[str, etree._Element], tag: str, parent: Provenance,
                 owner: str, read: Callable[[etree._Element, Provenance, str], _Read]
                 ) -> _Read | None:
        child = kids.get(tag)
        return read(child, self.where(child, parent), owner) if child is not None else None

    def limit(self, element: etree._Element, where: Provenance, owner: str) -> JointLimit:
        def read(key: str, required: bool = False) -> float | None:
            return self.number(element.get(key), f"<limit> {key}", where, owner,
                               required=required)

        return JointLimit(read("lower"), read("upper"), read("effort", True),
                          read("velocity", True), where)

    def dynamics(self, element: etree._Element, where: Provenance, owner: str) -> Dynamics:
        return Dynamics(self.number(element.get("damping"), "<dynamics> damping", where, owner),
                        self.number(element.get("friction"), "<dynamics> friction", where, owner),
                        where)

    def mimic(self, element: etree._Element, where: Provenance, owner: str) -> Mimic:
        target = element.get("joint") or ""
        if not target:
            self.issue("<mimic> joint is missing (required)", where, owner)
        # Absent: URDF's defaults; present but unreadable: None (and an issue).
        text = element.get("multiplier")
        multiplier = self.number(text, "<mimic> multiplier", where, owner,
                                 1.0 if text is None else None)
        text = element.get("offset")
        offset = self.number(text, "<mimic> offset", where, owner, 0.0 if text is None else None)
        return Mimic(target, multiplier, offset, where)

    def safety_controller(self, element: etree._Element, where: Provenance,
                          owner: str) -> SafetyController:
        def read(key: str) -> float | None:
            return self.number(element.get(key), f"<safety_controller> {key}", where, owner)

        return SafetyController(read("soft_lower_limit"), read("soft_upper_limit"),
                                read("k_position"), read("k_velocity"), where)

    def calibration(self, element: etree._Element, where: Provenance, owner: str) -> Calibration:
        return Calibration(self.number(element.get("rising"), "<calibration> rising", where, owner),
                           self.number(element.get("falling"), "<calibration> falling", where,
                                       owner),
                           where)

    def transmission(self, element: etree._Element, parent: Provenance) -> Transmission:
        where = self.where(element, parent)
        name = element.get("name") or ""
        owner = f"transmission:{name}"
        type_element = _first(element, "type")
        kind = element.get("type") or (_text(type_element) if type_element is not None else "")
        joints = tuple(TransmissionJoint(j.get("name") or "", _interfaces(j), self.where(j, where))
                       for j in _children(element, "joint"))
        shared = _first(element, "mechanicalReduction")
        shared_reduction = (self.number(_text(shared), "<mechanicalReduction>",
                                         self.where(shared, where), owner)
                            if shared is not None else None)
        actuators = []
        for actuator in _children(element, "actuator"):
            actuator_where = self.where(actuator, where)
            own = _first(actuator, "mechanicalReduction")
            reduction = (self.number(_text(own), "<mechanicalReduction>",
                                     self.where(own, actuator_where), owner)
                         if own is not None else shared_reduction)
            actuators.append(Actuator(actuator.get("name") or "", _interfaces(actuator),
                                      reduction, actuator_where))
        return Transmission(name, kind, joints, tuple(actuators), where)

    def gazebo(self, element: etree._Element, parent: Provenance) -> GazeboBlock:
        where = self.where(element, parent)
        tags = tuple(_tag(child) for child in element if isinstance(child.tag, str))
        plugins = tuple(plugin.get("filename") or "" for plugin in element.iter("plugin"))
        return GazeboBlock(element.get("reference"), tags, plugins, where)

    # -- shapes -----------------------------------------------------------------------------

    def box(self, element: etree._Element, where: Provenance, owner: str) -> Box | None:
        size = self.vector3(element.get("size"), "<box> size", where, owner, required=True,
                            bound=self.limits.length)
        return Box(size, where) if size is not None else None

    def required(self, element: etree._Element, key: str, where: Provenance,
                 owner: str) -> float | None:
        return self.number(element.get(key), f"<{_tag(element)}> {key}", where, owner,
                           required=True, bound=self.limits.length)

    def cylinder(self, element: etree._Element, where: Provenance,
                 owner: str) -> Cylinder | None:
        radius = self.required(element, "radius", where, owner)
        length = self.required(element, "length", where, owner)
        if radius is None or length is None:
            return None
        return Cylinder(radius, length, where)

    def capsule(self, element: etree._Element, where: Provenance, owner: str) -> Capsule | None:
        radius = self.required(element, "radius", where, owner)
        length = self.required(element, "length", where, owner)
        if radius is None or length is None:
            return None
        return Capsule(radius, length, where)

    def sphere(self, element: etree._Element, where: Provenance, owner: str) -> Sphere | None:
        radius = self.required(element, "radius", where, owner)
        return Sphere(radius, where) if radius is not None else None

    def mesh(self, element: etree._Element, where: Provenance, owner: str) -> MeshRef | None:
        filename = element.get("filename")
        if not filename:
            self.issue("<mesh> filename is missing (required)", where, owner)
            return None
        scale = self.vector3(element.get("scale"), "<mesh> scale", where, owner, (1.0, 1.0, 1.0),
                             bound=self.limits.scale)
        if scale is not None and any(0 < abs(v) < self.limits.smallest_scale for v in scale):
            self.issue(f"<mesh> scale=\"{_clip(element.get('scale') or '')}\" has a factor "
                       f"smaller than {self.limits.smallest_scale:g} in magnitude", where, owner)
            scale = (1.0, 1.0, 1.0)
        return MeshRef(filename, scale or (1.0, 1.0, 1.0), where)


_SHAPES = {"box": _RobotReader.box, "cylinder": _RobotReader.cylinder,
           "sphere": _RobotReader.sphere, "capsule": _RobotReader.capsule,
           "mesh": _RobotReader.mesh}


def _clip(text: str, limit: int = 80) -> str:
    """A value as quoted in a message: at most `limit` characters."""
    return text if len(text) <= limit else f"{text[:limit]}... ({len(text)} characters)"


#: A source file's state as `os.stat` gives it (size, modification and change times in ns,
#: inode), or None when it cannot be read.
_FileState = tuple[int, int, int, int] | None


class _ColumnFinder:
    """The column of an element's start tag on its source line (for expanded xacro, whose
    provenance carries lines only): the first `<tag` on the line, else 0. A file's lines are
    read again when its state changed (a finder outlives a parse: see `_decodings`); its
    state is taken once per parse (`new_parse`)."""

    def __init__(self) -> None:
        self._lines: dict[str, tuple[_FileState, list[str]]] = {}
        self._states: dict[str, _FileState] = {}

    def new_parse(self) -> None:
        """Look at the files again (they may have been saved since the last parse)."""
        self._states = {}

    def state(self, path: str) -> _FileState:
        """The file's state, as this parse first saw it."""
        if path not in self._states:
            try:
                info = os.stat(path)
                self._states[path] = (info.st_size, info.st_mtime_ns, info.st_ctime_ns,
                                      info.st_ino)
            except OSError:
                self._states[path] = None
        return self._states[path]

    def column(self, span: Span, tag: str) -> int:
        if not span.line:
            return 0
        state = self.state(span.path)
        known = self._lines.get(span.path)
        if known is None or known[0] != state:
            try:
                with open(span.path, encoding="utf-8", errors="replace") as handle:
                    lines = handle.read(MAX_SOURCE_CHARS).splitlines()
            except OSError:
                lines = []
            known = self._lines[span.path] = (state, lines)
        lines = known[1]
        if span.line > len(lines):
            return 0
        pattern = _START_TAGS.get(tag)
        if pattern is None:
            if len(_START_TAGS) >= _START_TAG_PATTERNS:
                _START_TAGS.clear()
            pattern = _START_TAGS[tag] = re.compile(
                rf"<(?:[\w.-]+:)?{re.escape(tag)}(?=[\s/>]|$)")
        match = pattern.search(lines[span.line - 1])
        return match.start() + 1 if match else 0


#: Tag -> the pattern of its start tag in a source line (a few dozen tags in a description).
_START_TAGS: dict[str, re.Pattern[str]] = {}
_START_TAG_PATTERNS = 1024


@dataclass(frozen=True)
class _Memoized:
    """A top-level element as an earlier parse read it: the value, the value issues it
    recorded, and the state of each source file its provenance was decoded from."""

    value: object
    issues: tuple[ValueIssue, ...]
    files: tuple[tuple[str, _FileState], ...]


#: Top-level elements remembered per file table (a description has hundreds).
_MEMOIZED_ELEMENTS = 20_000


class _Decodings:
    """What parses with one file table share: decoded positions and call chains (functions
    of the attribute text and the table alone), each attribute's provenance with the state
    of the file its column was read from, the column finder, and the top-level elements
    read (keyed by their bytes and parent provenance)."""

    def __init__(self) -> None:
        self.spans: dict[str, Span] = {}
        self.chains: dict[str, tuple[Span, ...]] = {}
        self.decoded: dict[tuple[str, str], tuple[Provenance, _FileState]] = {}
        self.elements: dict[tuple[bytes, Provenance], _Memoized] = {}
        self.columns = _ColumnFinder()


#: File table -> its decodings, for up to a few tables (the variants of a description and an
#: editor's saves parse expansions with the same table again and again).
_SHARED: dict[tuple[str, ...], _Decodings] = {}
_SHARED_TABLES = 8


def _decodings(files: tuple[str, ...]) -> _Decodings:
    """The shared decodings of this file table, ready for a new parse."""
    found = _SHARED.get(files)
    if found is None:
        found = _Decodings()
        if len(_SHARED) >= _SHARED_TABLES:
            _SHARED.clear()  # (safe while another thread parses: no iteration)
        _SHARED[files] = found
    found.columns.new_parse()
    return found


#: Characters of a source file read to find columns.
MAX_SOURCE_CHARS = 64 * 1024 * 1024


def _text(element: etree._Element) -> str:
    return (element.text or "").strip()


def _interfaces(element: etree._Element) -> tuple[str, ...]:
    return tuple(_text(child) for child in element if child.tag == "hardwareInterface")
