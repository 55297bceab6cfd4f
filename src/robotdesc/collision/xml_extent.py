"""Where each element of an XML text starts and ends, exactly, in the text as written.

A small scanner, not a parser: it pairs start and end tags and skips comments, CDATA,
processing instructions and the doctype, so that an element can be cut out of a file and
replaced without re-serialising (which would not be byte-faithful). Line numbers are counted
as expat (xacro's parser, and so robotdesc's provenance) counts them.
"""

from __future__ import annotations

import bisect
import re
from dataclasses import dataclass
from typing import Any

from robotdesc.errors import XmlSyntaxError

_LINE_BREAK = re.compile(r"\r\n|\r|\n")
_NAME = re.compile(r"[^\s/>]+")
_END_TAG = re.compile(r"</([^\s>]+)\s*>")


@dataclass(frozen=True)
class ElementExtent:
    """One element of a source text. Offsets index the (decoded) text.

    Attributes:
        name: the tag as written (with its prefix, e.g. "xacro:macro").
        start: offset of the start tag's `<`.
        end: offset just past the element (past `/>` or past the end tag's `>`).
        content_end: offset of the end tag's `<` (equal to `end` when self-closing).
        line: 1-based line of the start tag's `<`, counted as expat (xacro's parser) does:
            CRLF, CR and LF each end a line.
        parent: index of the enclosing element in the returned tuple, -1 at the top.
    """

    name: str
    start: int
    end: int
    content_end: int
    line: int
    parent: int

    @property
    def self_closing(self) -> bool:
        return self.content_end == self.end


def element_extents(text: str) -> tuple[ElementExtent, ...]:
    """Every element of an XML text in document order, skipping comments, CDATA, processing
    instructions and the doctype.

    Raises:
        XmlSyntaxError: the text is not well-formed enough to pair start and end tags (the
            message names the line).
    """
    breaks = [m.end() for m in _LINE_BREAK.finditer(text)]
    found: list[list[Any]] = []  # [name, start, end, content_end, line, parent]
    opened: list[int] = []
    pos = 0
    while (lt := text.find("<", pos)) >= 0:
        if text.startswith("<!--", lt):
            pos = _past(text, "-->", lt + 4)
        elif text.startswith("<![CDATA[", lt):
            pos = _past(text, "]]>", lt + 9)
        elif text.startswith("<?", lt):
            pos = _past(text, "?>", lt + 2)
        elif text.startswith("<!", lt):
            pos = _doctype_end(text, lt)
        elif text.startswith("</", lt):
            match = _END_TAG.match(text, lt)
            if not match or not opened or found[opened[-1]][0] != match.group(1):
                raise XmlSyntaxError(f"unexpected end tag at line {_line(breaks, lt)}")
            found[opened.pop()][2:4] = [match.end(), lt]
            pos = match.end()
        else:
            name = _NAME.match(text, lt + 1)
            if name is None:
                raise XmlSyntaxError(f"a '<' that starts no tag at line {_line(breaks, lt)}")
            close = _tag_end(text, lt, breaks)
            closed = text[close - 1] == "/"
            found.append([name.group(), lt, close + 1 if closed else -1,
                          close + 1 if closed else -1, _line(breaks, lt),
                          opened[-1] if opened else -1])
            if not closed:
                opened.append(len(found) - 1)
            pos = close + 1
    if opened:
        tag, line = found[opened[-1]][0], found[opened[-1]][4]
        raise XmlSyntaxError(f"<{tag}> at line {line} is not closed")
    return tuple(ElementExtent(*record) for record in found)


def _line(breaks: list[int], offset: int) -> int:
    return bisect.bisect_right(breaks, offset) + 1


def _past(text: str, marker: str, start: int) -> int:
    found = text.find(marker, start)
    if found < 0:
        raise XmlSyntaxError(f"'{marker}' missing")
    return found + len(marker)


def _tag_end(text: str, lt: int, breaks: list[int]) -> int:
    """Offset of the `>` that ends the tag starting at `lt` (quoted values may hold `>`)."""
    quote = ""
    for index in range(lt + 1, len(text)):
        char = text[index]
        if quote:
            quote = "" if char == quote else quote
        elif char in "\"'":
            quote = char
        elif char == ">":
            return index
        elif char == "<":
            break
    raise XmlSyntaxError(f"the tag at line {_line(breaks, lt)} is not closed")


def _doctype_end(text: str, lt: int) -> int:
    """Offset past a `<!DOCTYPE ...>` (with an internal subset in brackets)."""
    depth = 0
    for index in range(lt + 2, len(text)):
        char = text[index]
        if char == "[":
            depth += 1
        elif char == "]":
            depth -= 1
        elif char == ">" and depth <= 0:
            return index + 1
    raise XmlSyntaxError("the doctype is not closed")
