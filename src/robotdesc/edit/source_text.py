"""Start tags of a source file with the exact offsets of their attributes, and the xacro
macro each lies in: enough to change one attribute value without touching another byte.

A scanner, not a parser: it skips comments, CDATA, processing instructions and the doctype,
and counts lines as expat (xacro's parser, so robotdesc's provenance) does.
"""

from __future__ import annotations

import bisect
import dataclasses
import re
from dataclasses import dataclass

_LINE_BREAK = re.compile(r"\r\n|\r|\n")
_NAME = re.compile(r"[^\s/>]+")
_ATTRIBUTE = re.compile(r"""\s+([^\s=/>]+)\s*=\s*(?:"([^"]*)"|'([^']*)')""")
_END_TAG = re.compile(r"</([^\s>]+)\s*>")
_TAG_CLOSE = re.compile(r"\s*(/?>)")
_INDENT = re.compile(r"[ \t]*")


@dataclass(frozen=True)
class Attribute:
    """One attribute as written: its raw value and the offsets of the value (no quotes)."""

    name: str
    value: str
    start: int
    end: int


@dataclass(frozen=True)
class StartTag:
    """One start tag (or empty-element tag).

    Attributes:
        name: the tag as written ("link", "xacro:arm").
        start: offset of `<`; end: offset past `>`.
        line: 1-based line of `<`.
        attributes: in the order written.
        close: offset of the `/>` or `>` that ends the tag (where a new attribute goes).
        element_end: offset past the element (its end tag, or `end` when self-closing).
        macro: index (into the file's tags) of the enclosing `<xacro:macro>`, -1 for none.
    """

    name: str
    start: int
    end: int
    line: int
    attributes: tuple[Attribute, ...]
    close: int
    element_end: int
    macro: int

    def attribute(self, name: str) -> Attribute | None:
        return next((a for a in self.attributes if a.name == name), None)

    @property
    def local_name(self) -> str:
        return self.name.rpartition(":")[2]


@dataclass(frozen=True)
class SourceText:
    """A decoded source file and its start tags in document order."""

    path: str
    text: str
    tags: tuple[StartTag, ...]

    def at_line(self, line: int, local_name: str) -> list[StartTag]:
        """The tags named `local_name` (prefix ignored) starting on `line`."""
        return [t for t in self.tags if t.line == line and t.local_name == local_name]

    def macro_of(self, tag: StartTag) -> StartTag | None:
        return self.tags[tag.macro] if tag.macro >= 0 else None

    def body(self, macro: StartTag) -> str:
        return self.text[macro.end:macro.element_end]

    def line_of(self, offset: int) -> int:
        """The 1-based line of a text offset (lines counted as expat counts them)."""
        return len(_LINE_BREAK.findall(self.text, 0, offset)) + 1


def scan(path: str, text: str) -> SourceText:
    """Every start tag of `text`.

    Raises:
        ValueError: a tag or comment is not closed, or end tags do not pair.
    """
    breaks = [m.end() for m in _LINE_BREAK.finditer(text)]
    records: list[StartTag] = []
    opened: list[int] = []
    macros: list[int] = []
    pos = 0
    while (lt := text.find("<", pos)) >= 0:
        if text.startswith("<!--", lt):
            pos = _past(text, "-->", lt)
        elif text.startswith("<![CDATA[", lt):
            pos = _past(text, "]]>", lt)
        elif text.startswith("<?", lt):
            pos = _past(text, "?>", lt)
        elif text.startswith("<!", lt):
            pos = _past(text, ">", lt)
        elif text.startswith("</", lt):
            match = _END_TAG.match(text, lt)
            if not match or not opened or records[opened[-1]].name != match.group(1):
                raise ValueError(f"unpaired end tag at line {_line(breaks, lt)}")
            index = opened.pop()
            records[index] = dataclasses.replace(records[index], element_end=match.end())
            if macros and macros[-1] == index:
                macros.pop()
            pos = match.end()
        else:
            name = _NAME.match(text, lt + 1)
            if name is None:
                raise ValueError(f"a '<' that starts no tag at line {_line(breaks, lt)}")
            attributes, close = _attributes(text, name.end())
            empty = text.startswith("/>", close)
            end = close + (2 if empty else 1)
            records.append(StartTag(name.group(), lt, end, _line(breaks, lt), attributes,
                                    close, end if empty else -1, macros[-1] if macros else -1))
            if not empty:
                opened.append(len(records) - 1)
                if name.group() == "xacro:macro":
                    macros.append(len(records) - 1)
            pos = end
    if opened:
        raise ValueError(f"<{records[opened[-1]].name}> is not closed")
    return SourceText(path, text, tuple(records))


def _attributes(text: str, pos: int) -> tuple[tuple[Attribute, ...], int]:
    found: list[Attribute] = []
    while True:
        match = _ATTRIBUTE.match(text, pos)
        if match is None:
            break
        group = 2 if match.group(2) is not None else 3
        found.append(Attribute(match.group(1), match.group(group), match.start(group),
                               match.end(group)))
        pos = match.end()
    rest = _TAG_CLOSE.match(text, pos)
    if rest is None:
        raise ValueError(f"a tag is not closed near offset {pos}")
    return tuple(found), rest.start(1)


def _line(breaks: list[int], offset: int) -> int:
    return bisect.bisect_right(breaks, offset) + 1


def _past(text: str, marker: str, start: int) -> int:
    found = text.find(marker, start + 2)
    if found < 0:
        raise ValueError(f"'{marker}' missing")
    return found + len(marker)


def line_indent(text: str, offset: int) -> str:
    """The whitespace that starts the line holding `offset`."""
    begin = max(text.rfind("\n", 0, offset), text.rfind("\r", 0, offset)) + 1
    found = _INDENT.match(text, begin)
    return found.group(0) if found is not None else ""
