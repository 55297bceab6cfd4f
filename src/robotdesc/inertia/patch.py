"""A unified diff that replaces declared `<inertial>` blocks (or adds missing ones) in the
xacro/URDF sources with suggested ones. The user's files are never written: the diff is.

A block written inside a xacro macro, or one whose text holds `${...}` expressions, is not
patched (its text serves several links or computes its values); it is listed as skipped.
"""

from __future__ import annotations

import difflib
import os
import re
from collections.abc import Iterable
from dataclasses import dataclass

from robotdesc.inertia.suggest import Suggestion

_END = re.compile(r"</inertial\s*>")


@dataclass(frozen=True)
class Patch:
    """The diff and what could not go into it.

    Attributes:
        diff: unified diff text ("" when nothing changes).
        changed: (file, link) pairs patched.
        skipped: (link, reason) pairs left for a hand edit.
    """

    diff: str
    changed: tuple[tuple[str, str], ...]
    skipped: tuple[tuple[str, str], ...]


def build_patch(suggestions: Iterable[Suggestion], relative_to: str | None = None) -> Patch:
    """Apply the suggestions to copies of their source files and diff the copies.

    Args:
        suggestions: the blocks to write.
        relative_to: directory the diff's file names are relative to (default: cwd).
    """
    base = os.path.abspath(relative_to or os.getcwd())
    edits: dict[str, list[tuple[int, int, list[str], str]]] = {}
    skipped: list[tuple[str, str]] = []
    for item in suggestions:
        planned = _plan(item)
        if isinstance(planned, str):
            skipped.append((item.link, planned))
            continue
        path, start, end, lines = planned
        edits.setdefault(path, []).append((start, end, lines, item.link))
    chunks: list[str] = []
    changed: list[tuple[str, str]] = []
    for path in sorted(edits):
        original = _read_lines(path)
        updated = list(original)
        taken: list[tuple[int, int]] = []
        for start, end, lines, link in sorted(edits[path], key=lambda e: -e[0]):
            if any(start < b and a < end for a, b in taken):
                skipped.append((link, "overlaps another edit"))
                continue
            updated[start:end] = lines
            taken.append((start, end))
            changed.append((path, link))
        name = os.path.relpath(path, base) if _inside(path, base) else path
        chunks.extend(difflib.unified_diff(original, updated, f"a/{name}", f"b/{name}"))
    return Patch("".join(chunks), tuple(changed), tuple(skipped))


def _plan(item: Suggestion) -> tuple[str, int, int, list[str]] | str:
    """(file, first line index, end index, replacement lines) or why not."""
    if item.in_macro:
        return "the <inertial> is written inside a xacro macro; edit the macro's arguments"
    span = item.replaces or item.link_span
    if span is None or not span.line or not os.path.isfile(span.path):
        return "its source location is unknown"
    lines = _read_lines(span.path)
    index = span.line - 1
    if index >= len(lines):
        return f"line {span.line} is past the end of {span.path}"
    indent = lines[index][:len(lines[index]) - len(lines[index].lstrip())]
    if item.replaces is not None:
        if "<inertial" not in lines[index]:
            return f"no <inertial> at {span.path}:{span.line}"
        end = index
        if not re.search(r"<inertial[^>]*/>", lines[index]):
            while not _END.search(lines[end]):
                end += 1
                if end >= len(lines):
                    return f"no </inertial> after {span.path}:{span.line}"
        if not lines[index].lstrip().startswith("<inertial") or not (
                lines[end].rstrip().endswith("</inertial>") or lines[end].rstrip().endswith("/>")):
            return "the <inertial> shares its lines with other elements"
        block = "".join(lines[index:end + 1])
        if "${" in block or "$(" in block:
            return "the declared <inertial> computes its values with xacro expressions"
        return span.path, index, end + 1, _indent(item.block, indent)
    line = lines[index]
    if "<link" not in line:
        return f"no <link> at {span.path}:{span.line}"
    inner = indent + "  "
    if line.rstrip().endswith("/>"):
        opened = re.sub(r"\s*/>\s*$", ">", line.rstrip()) + "\n"
        return span.path, index, index + 1, [opened, *_indent(item.block, inner),
                                             f"{indent}</link>\n"]
    if not line.rstrip().endswith(">"):
        return f"the <link> tag at {span.path}:{span.line} spans several lines"
    return span.path, index + 1, index + 1, _indent(item.block, inner)


def _indent(block: str, indent: str) -> list[str]:
    return [f"{indent}{line}\n" for line in block.splitlines()]


def _read_lines(path: str) -> list[str]:
    with open(path, encoding="utf-8") as handle:
        return handle.readlines()


def _inside(path: str, base: str) -> bool:
    try:
        return os.path.commonpath([os.path.abspath(path), base]) == base
    except ValueError:
        return False
