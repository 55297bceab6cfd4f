"""Vocabulary rules: names URDF does not define (typos), and names that collide.

S201/S202 read the source document (`needs={"document"}`): the model keeps only what URDF
defines, so a misspelt `<orign>` or `uper="1"` is visible only in the XML. What URDF and
its common extensions define is one table, `robotdesc.rules.urdf_vocabulary`.
"""

from __future__ import annotations

import dataclasses
import difflib
import functools
import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

from lxml import etree

from robotdesc.diagnostics import Finding, Severity
from robotdesc.model.elements import Robot
from robotdesc.rules.registry import RuleContext, SourceDocument, rule
from robotdesc.rules.urdf_vocabulary import (
    GAZEBO_TAGS,
    LEGACY_ELEMENTS,
    URDF_ELEMENTS,
    ElementSpec,
    parents_of,
    spec_of,
)
from robotdesc.source import PROVENANCE_ATTR, Provenance, Span, decode_provenance
from robotdesc.xml_input import shared_root

#: Xacro's substitutions, as they appear in a file that was not expanded.
_SUBSTITUTION = re.compile(r"\$\{[^}]*\}|\$\([a-z]+[^)]*\)")
_XACRO_URIS = ("http://www.ros.org/wiki/xacro", "http://ros.org/wiki/xacro",
               "http://wiki.ros.org/xacro", "http://www.ros.org/xacro")


@dataclass(frozen=True)
class UnknownName:
    """One element or attribute the vocabulary does not know.

    Attributes:
        kind: "element" or "attribute".
        name: the unknown name.
        parent: the element it appears in (its own tag for an attribute).
        hint: what to write instead ("did you mean ...", or where it belongs).
        where: the element's provenance.
        element: a stable, line-free name for the finding.
    """

    kind: str
    name: str
    parent: str
    hint: str
    where: Provenance
    element: str


@rule("S201", "unknown-element", family="structure", severity=Severity.WARNING,
      needs=("document",))
def unknown_element(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds an element that URDF does not define where it is written: a misspelt tag
    (`<orign>`, `<inertail>`), a URDF element in the wrong place (`<origin>` directly in a
    `<link>`), or a Gazebo tag outside `<gazebo>`.

    The message says what was probably meant. The extensions descriptions commonly carry
    are known and not reported (`<gazebo>`, `<transmission>`, `<ros2_control>`,
    `<mujoco>`, `<sensor>`, pybullet's `<contact>`, ...; the table is
    `robotdesc/rules/urdf_vocabulary.py`), and the contents of an extension element are
    never judged. Namespaced elements (`xacro:*`, `drake:*`) are not judged either.

    Why is this bad?
    URDF parsers ignore elements they do not know, silently: a `<orign>` in a joint leaves
    the joint at the parent's origin, an `<inertail>` leaves the link massless, and a
    `<gravity>` written in a link instead of in `<gazebo reference=...>` turns nothing off.
    The robot loads and is wrong.

    Example
    ```xml
    <joint name="elbow" type="revolute">
      <parent link="upper_arm"/><child link="forearm"/>
      <orign xyz="0 0 0.3"/>
      <limit lower="-2" upper="2" effort="20" velocity="2"/>
    </joint>
    ```

    Use instead:
    ```xml
    <joint name="elbow" type="revolute">
      <parent link="upper_arm"/><child link="forearm"/>
      <origin xyz="0 0 0.3"/>
      <limit lower="-2" upper="2" effort="20" velocity="2"/>
    </joint>
    ```
    """
    if ctx.document is None:
        return
    for unknown in unknown_names(ctx.document):
        if unknown.kind == "element":
            yield Finding(f"<{unknown.name}> is not a URDF element inside <{unknown.parent}>"
                          f" and is ignored; {unknown.hint}", unknown.where, unknown.element)


@rule("S202", "unknown-attribute", family="structure", severity=Severity.WARNING,
      needs=("document",), opt_in=True)
def unknown_attribute(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds an attribute that URDF does not define on its element: a misspelt name
    (`uper="1"`, `<inertia iyx=...>`), or one that belongs to another element.

    Opt-in since issue 29: on the blind part 0 of 5 were worth fixing (a redundant symmetric
    entry, an attribute no consumer reads; docs/precision.md).

    The message names the closest attribute the element defines (preferring one that is
    missing). Known extension attributes (Isaac Sim's `dont_collapse`, Franka's dynamics
    parameters, ...) and namespaced attributes are not reported; attributes inside
    extension elements (`<gazebo>`, `<transmission>`, `<ros2_control>`, ...) are never
    judged.

    Why is this bad?
    The misspelt attribute is ignored, so the value falls back to URDF's default: a limit
    `uper="1"` leaves the upper limit at 0, and a misspelt inertia entry is a missing one
    (S110 reports that the entry is missing; this rule says which attribute was meant).

    Example
    ```xml
    <joint name="elbow" type="revolute">
      <parent link="upper_arm"/><child link="forearm"/>
      <limit lower="-2" uper="2" effort="20" velocity="2"/>
    </joint>
    ```

    Use instead:
    ```xml
    <joint name="elbow" type="revolute">
      <parent link="upper_arm"/><child link="forearm"/>
      <limit lower="-2" upper="2" effort="20" velocity="2"/>
    </joint>
    ```
    """
    if ctx.document is None:
        return
    for unknown in unknown_names(ctx.document):
        if unknown.kind == "attribute":
            yield Finding(f"<{unknown.parent}> has no attribute '{unknown.name}' (URDF "
                          f"ignores it); {unknown.hint}", unknown.where, unknown.element)


@rule("S203", "link-and-joint-share-name", family="structure", severity=Severity.ERROR)
def link_and_joint_share_name(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a joint whose name is also the name of a link.

    Why is this bad?
    URDF keeps links and joints apart, but SDFormat does not: Gazebo converts the URDF to
    SDF, where the links, joints and frames of a model share one name scope. A moving joint
    stays a joint next to the link; a fixed joint that the converter lumps into its parent
    is kept as a `//frame` named after the joint, next to a `//frame` named after the lumped
    link. Either way two frames share a name: libsdformat reports DUPLICATE_NAME for the
    SDFormat 1.7+ it converts to (Gazebo Fortress and later), and older versions rename one
    of them with a warning, which breaks plugins and controllers that refer to it. Tools that
    key frames by name (TF trees of some bridges, MuJoCo's converter) stumble too.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="wrist"/>
      <joint name="wrist" type="fixed"><parent link="base"/><child link="wrist"/></joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="wrist"/>
      <joint name="wrist_joint" type="fixed"><parent link="base"/><child link="wrist"/></joint>
    </robot>
    ```
    """
    links = {link.name: link for link in robot.links if link.name}
    for joint in robot.joints:
        link = links.get(joint.name)
        if link is not None:
            at = ""
            if link.where is not None:
                same = joint.where is not None and joint.where.span.path == link.where.span.path
                at = f" (the link is at {f'line {link.where.span.line}' if same else link.where})"
            kept_as = ("a frame, where a fixed joint is lumped," if joint.type == "fixed"
                       else "a joint")
            yield Finding(f"joint '{joint.name}' has the name of a link{at}; Gazebo's SDF "
                          f"conversion keeps it as {kept_as} in the link's name scope, a "
                          f"duplicate name (an error in SDFormat 1.7+): rename the joint "
                          f"(e.g. '{joint.name}_joint')", joint.where, f"joint:{joint.name}")


@rule("J109", "negative-joint-dynamics", family="joints", severity=Severity.ERROR)
def negative_joint_dynamics(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a joint whose `<dynamics>` sets a negative `damping` or `friction`.

    Why is this bad?
    Damping and friction take energy out of the joint. A negative damping feeds energy in:
    the joint accelerates by itself and the simulation blows up (Gazebo, MuJoCo and Drake
    accept the value and integrate it). Friction is a magnitude; a negative one is either
    refused or turned into a driving force. Usually a sign slipped in a xacro expression.

    Example
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="continuous">
        <parent link="base"/><child link="arm"/>
        <dynamics damping="-0.5" friction="0.1"/>
      </joint>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="continuous">
        <parent link="base"/><child link="arm"/>
        <dynamics damping="0.5" friction="0.1"/>
      </joint>
    </robot>
    ```
    """
    for joint in robot.joints:
        dynamics = joint.dynamics
        if dynamics is None:
            continue
        negative = [f"{name}={value:g}" for name, value in
                    (("damping", dynamics.damping), ("friction", dynamics.friction))
                    if value is not None and value < 0]
        if negative:
            yield Finding(f"joint '{joint.name}' has negative dynamics "
                          f"({', '.join(negative)}); damping and friction must be >= 0",
                          dynamics.where or joint.where, f"joint:{joint.name}/dynamics")


@rule("X201", "xacro-in-plain-urdf", family="xacro", severity=Severity.ERROR,
      needs=("document", "expansion"))
def xacro_in_plain_urdf(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a file read as plain URDF that still holds xacro: `${...}` or `$(...)`
    substitutions, or elements in the xacro namespace.

    Reported once, at the first place. robotdesc expands a file with xacro when its name
    ends in `.xacro` or it contains `<xacro:` tags; a `.urdf` with only substitutions is
    read as it is.

    Why is this bad?
    Every URDF consumer reads `${wheel_radius}` as text: urdfdom refuses the file, others
    read 0. The file is a xacro file with the wrong name, or a snippet meant to be included
    by one.

    Example
    ```xml
    <link name="wheel">
      <visual><geometry><cylinder radius="${wheel_radius}" length="0.05"/></geometry></visual>
    </link>
    ```

    Use instead (rename the file to `wheel.urdf.xacro` and declare the property, or expand
    it: `robotdesc expand wheel.urdf.xacro -o wheel.urdf`):
    ```xml
    <link name="wheel">
      <visual><geometry><cylinder radius="0.1" length="0.05"/></geometry></visual>
    </link>
    ```
    """
    if ctx.document is None or ctx.expansion.from_xacro:
        return
    first = first_xacro_use(ctx.document)
    if first is not None:
        what, line = first
        yield Finding(f"this file is read as plain URDF but contains xacro ({what}); name it "
                      f"*.urdf.xacro so that it is expanded, or expand it with `robotdesc "
                      f"expand`", Provenance(Span(ctx.document.path, line)), "robot")


# --- the document walk ----------------------------------------------------------------------


def unknown_names(document: SourceDocument) -> tuple[UnknownName, ...]:
    """Every element and attribute of `document` the vocabulary does not know."""
    return _unknown_names(document.xml, document.path, tuple(document.files))


@functools.lru_cache(maxsize=8)
def _unknown_names(xml: bytes, path: str, files: tuple[str, ...]) -> tuple[UnknownName, ...]:
    root = shared_root(xml)  # the model's parse already refused DOCTYPEs and bad XML
    if root is None or root.tag != "robot":
        return ()
    found: list[UnknownName] = []
    _Walker(path, files, found).visit(root, URDF_ELEMENTS["robot"], None, "robot")
    return _once_per_place(found) if files else tuple(found)  # files: expanded by xacro


def _once_per_place(found: list[UnknownName]) -> tuple[UnknownName, ...]:
    """One entry per written place: a typo in a macro body is one fix, however many times
    the macro is expanded (the count is added to the hint)."""
    first: dict[tuple[object, ...], UnknownName] = {}
    counts: dict[tuple[object, ...], int] = {}
    for unknown in found:
        key = (unknown.kind, unknown.name, unknown.parent, unknown.where.span)
        first.setdefault(key, unknown)
        counts[key] = counts.get(key, 0) + 1
    return tuple(dataclasses.replace(unknown, hint=f"{unknown.hint} (written once, expanded "
                                     f"{counts[key]} times)") if counts[key] > 1 else unknown
                 for key, unknown in first.items())


def first_xacro_use(document: SourceDocument) -> tuple[str, int] | None:
    """(what, line) of the first xacro element or substitution in `document`, or None."""
    root = shared_root(document.xml)
    if root is None:
        return None
    for element in root.iter():
        if not isinstance(element.tag, str):
            continue
        namespace = etree.QName(element).namespace
        if namespace in _XACRO_URIS:
            return f"<xacro:{etree.QName(element).localname}>", element.sourceline or 0
        for name, value in element.attrib.items():
            match = _SUBSTITUTION.search(value)
            if match:
                return f"{etree.QName(name).localname}=\"{match.group(0)}\"", \
                    element.sourceline or 0
        match = _SUBSTITUTION.search(element.text or "")
        if match:
            return f"<{etree.QName(element).localname}>{match.group(0)}", element.sourceline or 0
    return None


class _Walker:
    """Walks the judged part of the tree, collecting unknown names with provenance."""

    def __init__(self, path: str, files: tuple[str, ...], found: list[UnknownName]) -> None:
        self.path = path
        self.files = files
        self.found = found

    def where(self, element: etree._Element, inherited: Provenance | None) -> Provenance:
        value = element.get(PROVENANCE_ATTR) if self.files else None
        if value is not None:
            try:
                return decode_provenance(value, self.files)
            except (ValueError, IndexError):
                pass
        if self.files and inherited is not None:
            return inherited
        return Provenance(Span(self.path, element.sourceline or 0))

    def visit(self, element: etree._Element, spec: ElementSpec, inherited: _Where | None,
              owner: _Owner) -> None:
        where = _Where(self, element, inherited)
        tag = element.tag
        names = element.keys()  # attribute names (iterating an lxml element gives children)
        unknown = [name for name in names if name not in spec.attributes
                   and name != PROVENANCE_ATTR and not name.startswith("{")
                   and not spec.known_attribute(name)]
        if unknown:
            present = {name for name in names if not name.startswith("{")}
            for name in sorted(unknown):
                hint = _suggest(name, spec.attributes - present, spec.attributes)
                self.found.append(UnknownName(
                    "attribute", name, tag, hint or "it is not read by any URDF parser",
                    where.get(), f"{_owner_text(owner)}@{name}"))
        counts: dict[str, int] = {}
        for child in element:
            child_tag = child.tag
            if not isinstance(child_tag, str) or child_tag.startswith("{"):
                continue  # comments; namespaced elements (xacro:*, drake:*) are not URDF's
            index = counts.get(child_tag, 0)
            counts[child_tag] = index + 1
            child_owner = (owner, child, index)
            if child_tag in spec.children:
                child_spec = spec_of(child_tag)
                if child_spec is not None:
                    self.visit(child, child_spec, where, child_owner)
            elif not spec.known_child(child_tag) and spec.judge_children \
                    and not _restates_defaults(child, tag):
                self.found.append(UnknownName(
                    "element", child_tag, tag, _element_hint(child_tag, tag, spec),
                    _Where(self, child, where).get(), _owner_text(child_owner)))


class _Where:
    """An element's provenance, decoded only when a finding needs it: most elements of a
    large robot have none, and decoding every one was most of the walk."""

    def __init__(self, walker: _Walker, element: etree._Element,
                 inherited: _Where | None) -> None:
        self.walker, self.element, self.inherited = walker, element, inherited
        self.value: Provenance | None = None

    def get(self) -> Provenance:
        if self.value is None:
            parent = self.inherited.get() if self.inherited is not None else None
            self.value = self.walker.where(self.element, parent)
        return self.value


#: An element's place, built as the walk descends and named only when a finding needs it:
#: "robot", or (the parent's place, the element, its index among same-tag siblings).
_Owner = str | tuple["_Owner", etree._Element, int]


def _owner_text(owner: _Owner) -> str:
    """A stable name: `link:base`, `joint:j1/limit`, `link:base/visual[1]/origin`."""
    if isinstance(owner, str):
        return owner
    parent, child, index = owner
    tag = child.tag
    name = child.get("name")
    if parent == "robot" and name is not None and tag in ("link", "joint", "material"):
        return f"{tag}:{name}"
    return f"{_owner_text(parent)}/{tag}" + (f"[{index}]" if index else "")


def _suggest(name: str, preferred: set[str] | frozenset[str],
             allowed: frozenset[str]) -> str:
    """'did you mean X?' for the closest allowed name (missing ones first), or ""."""
    for pool in (preferred, allowed):
        match = _closest(name, pool)
        if match:
            return f"did you mean '{match}'?"
    return ""


def _closest(name: str, pool: Iterable[str]) -> str | None:
    lowered = {candidate.lower(): candidate for candidate in pool}
    if name.lower() in lowered:
        return lowered[name.lower()]
    matches = difflib.get_close_matches(name.lower(), list(lowered), n=1, cutoff=0.6)
    return lowered[matches[0]] if matches else None


#: xacro's directives: unprefixed, old xacro files meant them (xacro 1 took them, deprecated).
_XACRO_DIRECTIVES = frozenset({"include", "macro", "property", "arg", "if", "unless",
                               "insert_block", "element", "attribute"})


def _restates_defaults(element: etree._Element, parent: str) -> bool:
    """Whether `element` is a legacy element (`LEGACY_ELEMENTS`: `<joint_properties
    damping="0.0" friction="0.0"/>`) whose every value is the default of the element that
    replaced it: ignored, and nothing meant is lost."""
    legacy = LEGACY_ELEMENTS.get((parent, str(element.tag)))
    if legacy is None or len(element):
        return False
    defaults = legacy[1]
    try:
        return all(name in defaults and float(value) == defaults[name]
                   for name, value in element.attrib.items() if name != PROVENANCE_ATTR)
    except ValueError:  # "${damping}" left unexpanded, a word: not a default
        return False


def _element_hint(tag: str, parent: str, spec: ElementSpec) -> str:
    """Did-you-mean, else where the element belongs."""
    legacy = LEGACY_ELEMENTS.get((parent, tag))
    if legacy is not None:
        return (f"<{tag}> is early URDF's name for <{legacy[0]}>, which today's parsers read "
                f"instead: write <{legacy[0]} " + " ".join(f'{n}="..."' for n in legacy[1])
                + "/>")
    if tag in _XACRO_DIRECTIVES:
        return (f"<{tag}> is a xacro directive written without its prefix, which xacro 2 "
                f"leaves in the URDF as is: write <xacro:{tag}> (with "
                f"xmlns:xacro=\"http://www.ros.org/wiki/xacro\" on the robot)")
    match = _closest(tag, spec.children)
    if match:
        return f"did you mean <{match}>?"
    if tag in GAZEBO_TAGS:
        return (f"<{tag}> is a Gazebo tag: put it inside <gazebo reference=\"...\"> at the top "
                f"level of the robot")
    homes = parents_of(tag)
    if homes:
        return "it belongs in " + " or ".join(f"<{home}>" for home in homes)
    if URDF_ELEMENTS["robot"].known_child(tag):
        return f"<{tag}> belongs at the top level of the robot"
    allowed = ", ".join(f"<{c}>" for c in sorted(spec.children))
    return f"<{parent}> holds {allowed}" if allowed else f"<{parent}> holds no elements"
