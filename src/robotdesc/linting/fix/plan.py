"""Where a change of an expanded element goes in the xacro source, if anywhere.

An attribute is edited where its value is a literal: in the element's own start tag (inside
a macro body only when every element that body makes gets the same value), or, when the
value is exactly `${param}` of the enclosing macro, at the call site's argument (followed
outwards while the argument is itself a parameter). Anything else is computed: the fix is
not applicable, and the reason names the file:line of the expression.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable
from dataclasses import dataclass

from robotdesc.linting.fix.changes import AttributeChange, ExpandedIndex, NotApplicable
from robotdesc.linting.fix.source_text import SourceText, StartTag, scan
from robotdesc.source import Span
from robotdesc.xml_text import escape_attribute

_PARAMETER = re.compile(r"^\$\{\s*([A-Za-z_]\w*)\s*\}$")
_EXPRESSION = re.compile(r"\$\{([^}]*)\}")


@dataclass(frozen=True)
class Edit:
    """Replace text[start:end] of a source file by `text`.

    Attributes:
        line: the line of the start tag edited.
        group: the elements whose value this location sets (their ids), to check that a
            literal shared by several elements is changed for all of them alike.
        sites: for an argument, the `${param}` attributes of the macro body that lead to it.
        uses: for an argument, how many uses its parameter has in the macro body.
        target: the element (its id) the change asked for.
    """

    path: str
    start: int
    end: int
    text: str
    line: int
    group: frozenset[int] = frozenset()
    sites: frozenset[tuple[str, int]] = frozenset()
    uses: int = 0
    target: int = 0


class SourceCache:
    """Source files read once per run, decoded as UTF-8, with their bytes kept."""

    def __init__(self, allowed: Callable[[str], bool]) -> None:
        self._files: dict[str, SourceText | str] = {}
        self.raw: dict[str, bytes] = {}
        self.allowed = allowed

    def get(self, path: str) -> SourceText | str:
        """The scanned file, or why it cannot be edited."""
        if path not in self._files:
            self._files[path] = self._read(path)
        return self._files[path]

    def _read(self, path: str) -> SourceText | str:
        if not self.allowed(path):
            return f"{path} is outside the linted package"
        if os.path.islink(path) or not os.path.isfile(path):
            return f"{path} is not a regular file"
        with open(path, "rb") as handle:
            data = handle.read()
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            return f"{path} is not UTF-8"
        try:
            found = scan(path, text)
        except ValueError as error:
            return f"{path} cannot be scanned: {error}"
        self.raw[path] = data
        return found


def plan_change(change: AttributeChange, index: ExpandedIndex, files: SourceCache
                ) -> Edit | NotApplicable:
    """The source edit of one change."""
    where = index.where(change.element)
    span, chain = where.span, where.macro_stack
    tag_name = change.element.tag
    source = files.get(span.path)
    if isinstance(source, str):
        return NotApplicable(source)
    tags = source.at_line(span.line, tag_name)
    if len(tags) != 1:
        return NotApplicable(f"no single <{tag_name}> written at {span}")
    tag = tags[0]
    group = index.by_span.get((span.path, span.line, tag_name), [])
    depth, uses = 0, 0
    sites: frozenset[tuple[str, int]] = frozenset()
    while True:
        attribute = tag.attribute(change.attribute)
        members = frozenset(id(e) for e in group
                            if index.where(e).macro_stack[:depth] == chain[:depth])
        if attribute is None:
            if depth:
                macro = source.macro_of(tag)
                return NotApplicable(f"computed at {macro_span(source, macro)}: the default "
                                     f"of the macro's parameter")
            text = f' {change.attribute}="{_quote(change.value)}"'
            return Edit(span.path, tag.close, tag.close, text, tag.line, members)
        raw = attribute.value
        if "$" not in raw:
            return Edit(source.path, attribute.start, attribute.end, _quote(change.value),
                        tag.line, members, sites, uses)
        parameter = _PARAMETER.match(raw)
        macro = source.macro_of(tag)
        if parameter is None or macro is None or depth >= len(chain) \
                or parameter.group(1) not in macro_parameters(macro):
            return NotApplicable(f"computed at {source.path}:{tag.line}")
        name = parameter.group(1)
        if not depth:
            sites, uses = frozenset({(source.path, attribute.start)}), _uses(source.body(macro),
                                                                               name)
        call = chain[depth]
        caller = files.get(call.path)
        if isinstance(caller, str):
            return NotApplicable(caller)
        named = macro.attribute("name")
        macro_name = named.value if named is not None else ""
        calls = [t for t in caller.tags if t.line == call.line
                 and t.local_name == macro_name and t.name != "xacro:macro"]
        if len(calls) != 1:
            return NotApplicable(f"no single call of macro '{macro_name}' at {call}")
        source, tag = caller, calls[0]
        depth += 1
        change = AttributeChange(change.element, name, change.value)


def macro_parameters(macro: StartTag) -> set[str]:
    """The parameter names of a `<xacro:macro params="...">` (defaults and markers removed)."""
    params = macro.attribute("params")
    names = set()
    for item in (params.value.split() if params else ()):
        name = re.split(r":?=", item, maxsplit=1)[0].lstrip("*").rstrip("^|")
        names.add(name.rstrip("^"))
    return names


def macro_span(source: SourceText, macro: StartTag | None) -> Span:
    return Span(source.path, macro.line if macro else 0)


def _uses(body: str, name: str) -> int:
    word = re.compile(rf"(?<![\w.]){re.escape(name)}\b")
    return sum(len(word.findall(m.group(1))) for m in _EXPRESSION.finditer(body))


def _quote(value: str) -> str:
    return escape_attribute(value)
