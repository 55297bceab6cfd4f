"""Where a change of an expanded element goes in the xacro sources, if anywhere.

An attribute is edited where its value is written as a literal, following the provenance the
expansion records:
- in the element's own start tag (inside a macro body when every element that body makes
  gets the same value);
- when the value is exactly `${param}` of the enclosing macro, at the call site's argument
  (followed outwards while the argument is itself a parameter);
- when the value is exactly `${name}` of one global `<xacro:property name=... value=...>`,
  in the property's value (every use of the property must want the same change).
Anything else is computed: the change is refused, and the reason names the FILE:LINE of the
expression or property, relative to the package.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable

from robotdesc.edit.fix import Applicability, Edit, Fix
from robotdesc.edit.index import AttributeChange, Changes, ExpandedIndex, Refused, local
from robotdesc.edit.source_text import SourceText, StartTag, scan
from robotdesc.edit.values import merged_value
from robotdesc.expansion.packages import enclosing_package
from robotdesc.xml_text import escape_attribute

_PARAMETER = re.compile(r"^\$\{\s*([A-Za-z_]\w*)\s*\}$")
_EXPRESSION = re.compile(r"\$\{([^}]*)\}")


class SourceCache:
    """Source files read once per run, decoded as UTF-8, with their bytes kept.

    Args:
        root: the folder edits may go in (the linted package); reasons name files relative
            to it.
    """

    def __init__(self, root: str, allowed: Callable[[str], bool] | None = None) -> None:
        self.root = os.path.abspath(root)
        self._files: dict[str, SourceText | str] = {}
        self.raw: dict[str, bytes] = {}
        self.allowed = allowed or (lambda path: inside(path, self.root))

    def get(self, path: str) -> SourceText | str:
        """The scanned file, or why it cannot be edited."""
        if path not in self._files:
            self._files[path] = self._read(path)
        return self._files[path]

    def at(self, path: str, line: int) -> str:
        """FILE:LINE with FILE relative to the package when inside it."""
        name = os.path.relpath(path, self.root) if inside(path, self.root) else path
        return f"{name}:{line}" if line else name

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
            return f"{self.at(path, 0)} is not UTF-8"
        try:
            found = scan(path, text)
        except ValueError as error:
            return f"{self.at(path, 0)} cannot be scanned: {error}"
        self.raw[path] = data
        return found


def locate(change: AttributeChange, index: ExpandedIndex, files: SourceCache
           ) -> Edit | Refused | None:
    """The source edit of one change; None when the source already has the value."""
    where = index.where(change.element)
    span, chain = where.span, where.macro_stack
    tag_name = local(change.element.tag)
    source = files.get(span.path)
    if isinstance(source, str):
        return Refused(source)
    tags = source.at_line(span.line, tag_name)
    if len(tags) != 1:
        return Refused(f"no single <{tag_name}> written at {files.at(span.path, span.line)}")
    tag = tags[0]
    group = index.by_span.get((span.path, span.line, tag_name), [])
    depth, uses = 0, 0
    sites: frozenset[tuple[str, int]] = frozenset()
    attribute_name = change.attribute
    while True:
        attribute = tag.attribute(attribute_name)
        members = frozenset(id(e) for e in group
                            if index.where(e).macro_stack[:depth] == chain[:depth])
        if attribute is None:
            if depth:
                macro = source.macro_of(tag)
                return Refused(f"computed at {files.at(source.path, macro.line if macro else 0)}"
                               ": the default of the macro's parameter")
            text = f' {attribute_name}="{escape_attribute(change.value)}"'
            return Edit(span.path, tag.close, tag.close, text, tag.line, members)
        raw = attribute.value
        if "$" not in raw:
            merged = merged_value(raw, change.value, tolerance=change.tolerance)
            if merged is None:
                return None
            return Edit(source.path, attribute.start, attribute.end, escape_attribute(merged),
                        tag.line, members, sites, uses)
        parameter = _PARAMETER.match(raw)
        macro = source.macro_of(tag)
        name = parameter.group(1) if parameter else ""
        if not parameter or macro is None or depth >= len(chain) \
                or name not in macro_parameters(macro):
            if parameter:
                if sites and uses > len(sites):
                    return Refused(f"computed at {files.at(source.path, tag.line)}: the "
                                   f"argument is used in {uses} places of its macro")
                return _property_edit(name, change, source, attribute.start, files, index,
                                      members)
            return Refused(f"computed at {files.at(source.path, tag.line)}: the expression "
                           f"'{raw}'")
        if not depth:
            sites = frozenset({(source.path, attribute.start)})
            uses = _uses(source.body(macro), name)
        call = chain[depth]
        caller = files.get(call.path)
        if isinstance(caller, str):
            return Refused(caller)
        named = macro.attribute("name")
        macro_name = named.value if named is not None else ""
        calls = [t for t in caller.tags if t.line == call.line
                 and t.local_name == macro_name and t.name != "xacro:macro"]
        if len(calls) != 1:
            return Refused(f"no single call of macro '{macro_name}' at "
                           f"{files.at(call.path, call.line)}")
        source, tag = caller, calls[0]
        depth += 1
        attribute_name = name


def _property_edit(name: str, change: AttributeChange, source: SourceText, offset: int,
                   files: SourceCache, index: ExpandedIndex, members: frozenset[int]
                   ) -> Edit | Refused | None:
    """The edit of the value of the one global `<xacro:property name=NAME>` a `${NAME}` at
    `offset` of `source` reads."""
    found: list[tuple[SourceText, StartTag]] = []
    texts: list[SourceText] = []
    for path in dict.fromkeys((index.source, *index.files)):
        text = files.get(path)
        if isinstance(text, str):
            continue
        texts.append(text)
        found += [(text, t) for t in text.tags if t.local_name == "property"
                  and t.name != "property" and _value(t, "name") == name]
    where = files.at(source.path, source.line_of(offset))
    if not found:
        return Refused(f"computed at {where}: '${{{name}}}' is neither a parameter of its "
                       f"macro nor a property defined in the package")
    if len(found) > 1:
        places = ", ".join(files.at(t.path, tag.line) for t, tag in found)
        return Refused(f"computed at {where}: the property '{name}' is defined "
                       f"{len(found)} times ({places})")
    text, definition = found[0]
    at = files.at(text.path, definition.line)
    value = definition.attribute("value")
    if definition.macro >= 0:
        return Refused(f"computed at {at}: the property '{name}' is local to a macro")
    if value is None or "$" in value.value:
        return Refused(f"computed at {at}: the property '{name}' has no literal value")
    merged = merged_value(value.value, change.value, tolerance=change.tolerance)
    if merged is None:
        return None
    uses = sum(_uses(t.text, name) for t in texts)
    return Edit(text.path, value.start, value.end, escape_attribute(merged), definition.line,
                members, frozenset({(source.path, offset)}), uses)


def _value(tag: StartTag, name: str) -> str | None:
    found = tag.attribute(name)
    return found.value if found is not None else None


def macro_parameters(macro: StartTag) -> set[str]:
    """The parameter names of a `<xacro:macro params="...">` (defaults and markers removed)."""
    params = macro.attribute("params")
    names = set()
    for item in (params.value.split() if params else ()):
        name = re.split(r":?=", item, maxsplit=1)[0].lstrip("*").rstrip("^|")
        names.add(name.rstrip("^"))
    return names


def _uses(body: str, name: str) -> int:
    word = re.compile(rf"(?<![\w.]){re.escape(name)}\b")
    return sum(len(word.findall(m.group(1))) for m in _EXPRESSION.finditer(body))


def inside(path: str, root: str) -> bool:
    """Whether `path` is inside `root` (symbolic links resolved)."""
    try:
        real, base = os.path.realpath(path), os.path.realpath(root)
        return os.path.commonpath([real, base]) == base
    except ValueError:
        return False


def changes_fix(changes: Changes, index: ExpandedIndex, files: SourceCache,
                applicability: Applicability) -> Fix:
    """The fix of attribute changes: their edits, or display-only with the first refusal."""
    if isinstance(changes, Refused):
        return Fix.refused(changes.reason)
    edits: list[Edit] = []
    for change in changes:
        edit = locate(change, index, files)
        if isinstance(edit, Refused):
            return Fix.refused(edit.reason)
        if edit is not None:
            edits.append(Edit(edit.path, edit.start, edit.end, edit.replacement, edit.line,
                              edit.group, edit.sites, edit.uses, id(change.element)))
    if not edits:
        return Fix.refused("the source already has the fixed values")
    return Fix(tuple(edits), applicability)


def package_folder(path: str) -> str:
    """The folder edits may go in: the ROS package holding `path`, else its folder."""
    found = enclosing_package(os.path.abspath(path))
    return str(found[1]) if found else os.path.dirname(os.path.abspath(path))
