"""A save that only changes literal attribute values, applied to the previous expansion.

The realistic edit in an editor changes a number: a limit, an axis, a mass. When the saved
file differs from the text the last lint expanded only in attribute values written as plain
literals (no `${...}`, no `$(...)`, no entity) of ordinary elements (not xacro directives), each
on the line of its element's start tag, the expanded document is edited in place: every
element whose provenance names that file and line gets the new value where it had the old
one. That is what xacro would have produced (it copies literal attributes of ordinary elements
unchanged), without starting the expansion worker. Anything else (a changed line count, a
tag, an expression, a xacro directive, an element not found with the old value) is `None`:
the caller expands again.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from robotdesc.source import PROVENANCE_ATTR

#: Most changed lines handled in place (a larger edit is expanded again).
MAX_CHANGED_LINES = 20
#: The start tags of a line (a name after "<": no end tags, comments or declarations).
_START_TAG = re.compile(rb"<([A-Za-z_][\w.\-]*(?::[A-Za-z_][\w.\-]*)?)")
_ATTRIBUTE = re.compile(rb"""([A-Za-z_][\w.:\-]*)(\s*=\s*)(?:"([^"<&]*)"|'([^'<&]*)')""")
#: Xacro directives, also as the unprefixed tags old xacro files use.
_DIRECTIVES = {b"property", b"macro", b"include", b"arg", b"if", b"unless", b"insert_block",
               b"call", b"element", b"attribute"}


@dataclass(frozen=True)
class ValueChange:
    """One attribute value changed on one line.

    Attributes:
        line: the line (1-based) of the element's start tag.
        attribute: the attribute's name.
        old: its value before.
        new: its value now.
    """

    line: int
    attribute: str
    old: str
    new: str


def literal_changes(before: bytes, after: bytes) -> tuple[ValueChange, ...] | None:
    """The literal attribute values that changed between two texts of one file; None when
    anything else changed (or nothing did)."""
    old_lines, new_lines = before.split(b"\n"), after.split(b"\n")
    if len(old_lines) != len(new_lines):
        return None
    differing = [n for n, (a, b) in enumerate(zip(old_lines, new_lines)) if a != b]
    if not differing or len(differing) > MAX_CHANGED_LINES:
        return None
    changes: list[ValueChange] = []
    for number in differing:
        found = _line_changes(number + 1, old_lines[number], new_lines[number])
        if found is None:
            return None
        changes += found
    return tuple(changes)


def _line_changes(line: int, old: bytes, new: bytes) -> list[ValueChange] | None:
    tags = _START_TAG.findall(old)
    if len(tags) != 1 or _START_TAG.findall(new) != tags or b":" in tags[0] \
            or tags[0] in _DIRECTIVES or b"$" in old + new:
        return None
    if _ATTRIBUTE.sub(rb'\1\2""', old) != _ATTRIBUTE.sub(rb'\1\2""', new):
        return None  # more than values changed (a name, a tag, text between)
    before, after = _ATTRIBUTE.findall(old), _ATTRIBUTE.findall(new)
    if [a[0] for a in before] != [a[0] for a in after]:
        return None
    changes = []
    for (name, _, dq_old, sq_old), (_, _, dq_new, sq_new) in zip(before, after):
        value_old, value_new = dq_old or sq_old, dq_new or sq_new
        if value_old != value_new:
            try:
                changes.append(ValueChange(line, name.decode("ascii"),
                                           value_old.decode("utf-8"), value_new.decode("utf-8")))
            except UnicodeDecodeError:
                return None
    return changes or None


def patch_document(xml: bytes, files: tuple[str, ...], path: str,
                   changes: tuple[ValueChange, ...]) -> bytes | None:
    """`xml` (an expansion with provenance over the file table `files`) with `changes` of
    `path` applied to every element written at a changed line; None when an element written
    there does not have the old value (the caller expands again)."""
    indexes = [str(i).encode() for i, name in enumerate(files) if name == path]
    if not indexes:
        return None
    for change in changes:
        sites = [index + b":" + str(change.line).encode() for index in indexes]
        name = re.escape(change.attribute.encode())
        old = _escaped(change.old)
        attribute = re.compile(rb"(\s" + name + rb'=")' + re.escape(old) + rb'"')
        replacement = _escaped(change.new)
        parts: list[bytes] = []
        done = 0
        for start, end in _tags_at(xml, sites):
            edited, count = attribute.subn(lambda m: m.group(1) + replacement + b'"',
                                           xml[start:end])
            if count != 1:
                return None
            parts += [xml[done:start], edited]
            done = end
        xml = b"".join(parts) + xml[done:] if parts else xml
    return xml


def _tags_at(xml: bytes, sites: list[bytes]) -> list[tuple[int, int]]:
    """(start, end) offsets of the start tags whose provenance attribute names one of
    `sites` ("FILE_INDEX:LINE") as the element's own position, in document order."""
    found: list[tuple[int, int]] = []
    for site in sites:
        needle = PROVENANCE_ATTR.encode() + b'="' + site
        at = xml.find(needle)
        while at >= 0:
            after = at + len(needle)
            start = xml.rfind(b"<", 0, at)
            end = xml.find(b">", after)
            if (xml[at - 1:at].isspace() and xml[after:after + 1] in (b'"', b";", b"|", b"*")
                    and start >= 0 and end >= 0 and _NAME_START.match(xml, start + 1)
                    and xml.find(b">", start, at) < 0 and xml.find(b"<", after, end) < 0):
                found.append((start, end + 1))
            at = xml.find(needle, after)
    return sorted(set(found))


#: The first character of an element name.
_NAME_START = re.compile(rb"[A-Za-z_]")


def _escaped(value: str) -> bytes:
    """An attribute value as the expansion writes it between double quotes."""
    return (value.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
            .replace('"', "&quot;").encode("utf-8"))
