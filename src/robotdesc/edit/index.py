"""The expanded document with each element's provenance, and what a fix changes in it: an
attribute value of an expanded element. Where the change goes in the sources is locate.py's."""

from __future__ import annotations

import re
from dataclasses import dataclass

from lxml import etree

from robotdesc.source import PROVENANCE_ATTR, Provenance, Span, decode_provenance

_ELEMENT = re.compile(r"^(link|joint):([^/]+)((?:/\w+(?:\[\d+\])?)*)$")
_STEP = re.compile(r"/(\w+)(?:\[(\d+)\])?")


@dataclass(frozen=True)
class AttributeChange:
    """Set `attribute` of one expanded element to `value` (adding it when absent).

    Attributes:
        tolerance: relative, the rule's: a written number this close to the new one is
            left as written (robotdesc.edit.values.SIX_DIGITS for a suggested `<inertial>`).
    """

    element: etree._Element  # of the expanded document
    attribute: str
    value: str
    tolerance: float = 1e-9


@dataclass(frozen=True)
class Refused:
    """Why a change cannot be written back (names the source FILE:LINE when there is one)."""

    reason: str


#: What a fixer returns: the changes, or why there are none.
Changes = list[AttributeChange] | Refused


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
            self.by_span.setdefault((span.path, span.line, local(element.tag)), []).append(
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
        """The expanded element a diagnostic's element name points to: "link:a",
        "joint:j/limit", "link:a/collision[1]/geometry/mesh" (index 0 when not given)."""
        match = _ELEMENT.match(name or "")
        if match is None:
            return None
        kind, owner, path = match.groups()
        found: etree._Element | None = (self.links if kind == "link" else self.joints).get(owner)
        for step in _STEP.finditer(path):
            if found is None:
                return None
            children = list(found.iterchildren(step.group(1)))
            position = int(step.group(2) or 0)
            found = children[position] if position < len(children) else None
        return found


def local(tag: object) -> str:
    """The local name of an element's tag ("" for comments and processing instructions)."""
    return tag.rpartition("}")[2] if isinstance(tag, str) else ""
