"""A unified diff that swaps the `<collision>` elements in a robot's xacro sources for new ones.

Every element of an expanded description carries the file and line of its start tag (see
robotdesc.source); xml_extent.py finds each element's exact extent in the source text.
`build_patch` replaces each link's first `<collision>` by the new elements (at its
indentation), removes the link's other `<collision>` elements (or, for a link without any,
inserts them before its `</link>`), and writes the changes as a unified diff with `a/` and
`b/` prefixes, relative to a root folder named in the patch's comment header (`git apply` or
`patch -p1` run in that folder). Nothing here writes a file: the patch is returned as bytes.

A link is left out, and listed in the header, when its text also makes another link (a macro
called several times, a file included twice), when the element is not a literal start tag at
its recorded line, when it comes from a snippet robotdesc generated, or when its file cannot
be read as UTF-8 XML.
"""

from __future__ import annotations

import os
import re
import textwrap
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from lxml import etree

from robotdesc.collision.manifest import read_manifest
from robotdesc.collision.xml_extent import ElementExtent, element_extents
from robotdesc.edit.engine import apply_edits, resolve_conflicts, unified_diff
from robotdesc.edit.fix import Edit, Fix
from robotdesc.errors import XmlSyntaxError
from robotdesc.expansion.packages import enclosing_package
from robotdesc.model.elements import Link, Robot
from robotdesc.source import Provenance

#: The reason given for a link whose `<collision>` already comes from this run's snippet.
UP_TO_DATE = "up to date"
#: (link name, folder of the file the elements go into) -> the new `<collision>` elements.
Render = Callable[[str, str], Sequence[etree._Element]]

_REST_OF_LINE = re.compile(r"[ \t]*(?:\r\n|\n|\r|\Z)")
_DECLARED_ENCODING = re.compile(r"""<\?xml[^>]*?encoding\s*=\s*["']([^"']+)""")
_UTF8 = {"utf-8", "utf8", "us-ascii", "ascii"}


@dataclass(frozen=True)
class Skipped:
    """A link the patch leaves out, and why."""

    link: str
    reason: str


@dataclass(frozen=True)
class XacroPatch:
    """The patch and what it does.

    Attributes:
        text: the patch file: comment header, then the unified diff (may hold no diff).
        root: the folder the patch's paths are relative to (absolute; "" when nothing to patch).
        files: the source files the patch changes (absolute).
        patched: the links whose `<collision>` elements the patch swaps.
        skipped: the links it leaves out.
    """

    text: bytes
    root: str
    files: tuple[str, ...]
    patched: tuple[str, ...]
    skipped: tuple[Skipped, ...]


def build_patch(robot: Robot, links: Sequence[str], render: Render, out_dir: str,
                patch_name: str, *, relative_meshes: bool = False) -> XacroPatch:
    """The patch that puts the new `<collision>` elements of `links` into the xacro sources.

    Args:
        robot: the expanded description (with provenance).
        links: the links with new collision geometry, in the order to report them.
        render: the new `<collision>` elements of a link, for a file in the given folder.
        out_dir: the folder the patch is written to (its header gives paths from there).
        patch_name: the patch's file name in `out_dir`.
        relative_meshes: the mesh paths are relative (`out_dir` is in no ROS package).
    """
    out_dir = os.path.abspath(out_dir)
    planner = _Planner(robot, render, out_dir)
    edits: dict[str, list[_Edit]] = {}
    patched, skipped, literal = [], [], []
    planned_links: list[tuple[str, list[_Edit]]] = []
    for name in links:
        try:
            planned_links.append((name, planner.link_edits(name)))
        except _Unpatchable as why:
            skipped.append(Skipped(name, str(why)))
    fixes = resolve_conflicts([Fix(tuple(Edit(e.path, e.start, e.end, e.text, e.line)
                                         for e in planned)) for _, planned in planned_links])
    for (name, planned), fix in zip(planned_links, fixes):
        if not fix.applicable:
            skipped.append(Skipped(name, "its text overlaps another link's change"))
            continue
        for edit in planned:
            edits.setdefault(edit.path, []).append(edit)
        patched.append(name)
        positions = [planner.where((e.path, e.line)) for e in planned if e.expressions]
        if positions:
            literal.append(f"{name} ({', '.join(positions)})")
    files = tuple(sorted(edits))
    root = _root(files, robot.source)
    diff = []
    for path in files:
        text = planner.source(path).text
        change = apply_edits(path, text.encode("utf-8"),
                             {(e.start, e.end): e.text for e in edits[path]})
        if change is not None:
            diff.append(unified_diff(_short(path, root), text, change.after.decode("utf-8")))
    header = _header(out_dir, patch_name, root, files, patched, skipped, literal,
                     _escaping(files, out_dir) if relative_meshes else [])
    return XacroPatch(("".join(header + diff)).encode("utf-8"), root, files, tuple(patched),
                      tuple(skipped))


# --- one link ---------------------------------------------------------------------------


class _Unpatchable(Exception):
    """Why a link cannot be patched (its message is shown to the user)."""


@dataclass(frozen=True)
class _Source:
    path: str
    text: str
    extents: tuple[ElementExtent, ...]
    newline: str


@dataclass(frozen=True)
class _Edit:
    """Replace text[start:end] of the file at `path` by `text` (given to the one edit
    engine, robotdesc.edit, as an `Edit`; `expressions` is for the patch's header)."""

    path: str
    start: int
    end: int
    text: str
    line: int
    expressions: bool = False


class _Planner:
    """The edits for one link at a time; knows which source spans make which links and keeps
    each source file read and scanned once."""

    def __init__(self, robot: Robot, render: Render, out_dir: str) -> None:
        self.robot = robot
        self.render = render
        self.out_dir = out_dir
        self.counts = Counter(_key(c.where) for link in robot.links for c in link.collisions
                              if c.where)
        self.owners: dict[str, dict[tuple[str, int], set[str]]] = {"collision": {}, "link": {}}
        for link in robot.links:
            for collision in link.collisions:
                if collision.where:
                    self.owners["collision"].setdefault(_key(collision.where),
                                                        set()).add(link.name)
            if link.where:
                self.owners["link"].setdefault(_key(link.where), set()).add(link.name)
        self.sources: dict[str, _Source | str] = {}
        self.generated: dict[str, frozenset[str]] = {}  # folder -> files its manifest lists

    def link_edits(self, name: str) -> list[_Edit]:
        """Replace the link's first `<collision>`, delete its others (or insert, when none).

        Raises:
            _Unpatchable: the link cannot be changed in its sources alone.
        """
        link = self.robot.link(name)
        if link is None:
            raise _Unpatchable("not in the description")
        if not link.collisions:
            return [self.insertion(link)]
        located: list[tuple[_Source, ElementExtent]] = []
        seen: Counter[tuple[str, int]] = Counter()
        for collision in link.collisions:
            if collision.where is None or not collision.where.span.line:
                raise _Unpatchable("a <collision> has no source position")
            key = _key(collision.where)
            self.check_owner(key, name, "collision")
            self.check_not_generated(key)
            source = self.source(key[0])
            found = [e for e in source.extents if e.name == "collision" and e.line == key[1]]
            if len(found) != self.counts[key]:
                raise _Unpatchable(f"{self.where(key)} holds {len(found)} <collision> start "
                                   f"tag(s) where the expansion made {self.counts[key]} (not "
                                   "a literal <collision>, or the file changed since)")
            located.append((source, found[seen[key]]))
            seen[key] += 1
        first_source, first = located[0]
        new = _render(self.render(name, os.path.dirname(first_source.path)),
                      _indent(first_source.text, first.start), first_source.newline)
        edits = [_Edit(first_source.path, first.start, first.end, new, first.line,
                       _has_expressions(first_source.text[first.start:first.end]))]
        for source, extent in located[1:]:
            start, end = _whole_lines(source.text, extent.start, extent.end)
            edits.append(_Edit(source.path, start, end, "", extent.line,
                               _has_expressions(source.text[extent.start:extent.end])))
        return edits

    def insertion(self, link: Link) -> _Edit:
        """Insert the new elements before the `</link>` of a link that has no `<collision>`."""
        if link.where is None or not link.where.span.line:
            raise _Unpatchable("its <link> has no source position")
        key = _key(link.where)
        self.check_owner(key, link.name, "link")
        source = self.source(key[0])
        found = [i for i, e in enumerate(source.extents) if e.name == "link" and e.line == key[1]]
        if len(found) != 1:
            raise _Unpatchable(f"{self.where(key)} holds no single literal <link> start tag")
        extent = source.extents[found[0]]
        if extent.self_closing:
            raise _Unpatchable(f"it has no <collision> and its <link> at {self.where(key)} "
                               "is self-closing")
        text = source.text
        children = [e for e in source.extents if e.parent == found[0]]
        child_indent = next((_indent(text, c.start) for c in children
                             if not text[_line_start(text, c.start):c.start].strip()),
                            _indent(text, extent.start) + "  ")
        new = _render(self.render(link.name, os.path.dirname(source.path)), child_indent,
                      source.newline)
        at = _line_start(text, extent.content_end)
        if text[at:extent.content_end].strip():  # `</link>` follows other text on its line
            return _Edit(source.path, extent.content_end, extent.content_end, new, key[1])
        return _Edit(source.path, at, at, child_indent + new + source.newline, key[1])

    def check_owner(self, key: tuple[str, int], link: str, kind: str) -> None:
        made = self.owners[kind].get(key, set())
        if made - {link}:
            raise _Unpatchable(f"its <{kind}> at {self.where(key)} makes {len(made)} links "
                               "(a macro called more than once, or a file included more "
                               "than once)")

    def check_not_generated(self, key: tuple[str, int]) -> None:
        """Refuse a file that a `robotdesc collision` manifest lists (a generated snippet)."""
        folder, name = os.path.split(key[0])
        if folder not in self.generated:
            manifest = read_manifest(folder)
            self.generated[folder] = frozenset(manifest.files) if manifest else frozenset()
        if name not in self.generated[folder]:
            return
        if os.path.realpath(folder) == os.path.realpath(self.out_dir):
            raise _Unpatchable(f"{UP_TO_DATE}: its <collision> comes from {self.where(key)}, "
                               "which this run rewrote")
        raise _Unpatchable(f"its <collision> comes from {self.where(key)}, an output of "
                           "another `robotdesc collision` run: regenerate that folder instead")

    def source(self, path: str) -> _Source:
        if path not in self.sources:
            self.sources[path] = _read_source(path)
        found = self.sources[path]
        if isinstance(found, str):
            raise _Unpatchable(found)
        return found

    def where(self, key: tuple[str, int]) -> str:
        """FILE:LINE with FILE relative to the output folder (as in the xacro snippet)."""
        return f"{_short(key[0], self.out_dir)}:{key[1]}"


def _read_source(path: str) -> _Source | str:
    """The file decoded and scanned, or why it cannot be patched."""
    try:
        with open(path, "rb") as stream:
            data = stream.read()
        text = data.decode("utf-8")
    except OSError as error:
        return f"{os.path.basename(path)} cannot be read: {error.strerror}"
    except UnicodeDecodeError:
        return f"{os.path.basename(path)} is not UTF-8"
    declared = _DECLARED_ENCODING.search(text[:200])
    if declared and declared.group(1).lower() not in _UTF8:
        return f"{os.path.basename(path)} declares the encoding {declared.group(1)} (only UTF-8 is patched)"
    try:
        extents = element_extents(text)
    except XmlSyntaxError as error:
        return f"{os.path.basename(path)} cannot be scanned as XML: {error}"
    return _Source(path, text, extents, "\r\n" if "\r\n" in text else "\n")


# --- text -------------------------------------------------------------------------------


def _render(elements: Sequence[etree._Element], indent: str, newline: str) -> str:
    """The elements pretty-printed; every line after the first indented by `indent`."""
    blocks = [etree.tostring(e, pretty_print=True, encoding="unicode").rstrip("\n")
              for e in elements]
    text = "\n".join(blocks).replace("${", "$${").replace("$(", "$$(")  # xacro: literal
    return (newline + indent).join(text.split("\n"))


def _line_start(text: str, offset: int) -> int:
    return max(text.rfind("\n", 0, offset), text.rfind("\r", 0, offset)) + 1


def _indent(text: str, offset: int) -> str:
    """The leading blanks of the line holding `offset`."""
    start = _line_start(text, offset)
    line = text[start:offset]
    return line[:len(line) - len(line.lstrip(" \t"))]


def _whole_lines(text: str, start: int, end: int) -> tuple[int, int]:
    """The range to delete for an element: its whole lines when nothing else is on them."""
    before = _line_start(text, start)
    after = _REST_OF_LINE.match(text, end)
    if text[before:start].strip(" \t") or after is None:
        return start, end
    return before, after.end()


def _has_expressions(text: str) -> bool:
    return "${" in text or "$(" in text


# --- paths and the header -----------------------------------------------------------------


def _root(files: Sequence[str], source: str) -> str:
    """The package of the description when it holds every file, else their common folder."""
    if not files:
        return ""

    package = enclosing_package(source) if source else None
    if package is not None:
        root = os.path.abspath(package[1])
        if all(os.path.commonpath([root, os.path.abspath(f)]) == root for f in files):
            return root
    return os.path.commonpath([os.path.dirname(os.path.abspath(f)) for f in files])


def _escaping(files: Sequence[str], out_dir: str) -> list[str]:
    """Patched files in a ROS package that does not hold `out_dir` (relative paths leave it)."""
    found = []
    for path in files:
        package = enclosing_package(path)
        if package is not None:
            root = os.path.realpath(package[1])
            if os.path.commonpath([root, os.path.realpath(out_dir)]) != root:
                found.append(path)
    return found


def _header(out_dir: str, patch_name: str, root: str, files: Sequence[str],
            patched: Sequence[str], skipped: Sequence[Skipped], literal: Sequence[str],
            escaping: Sequence[str]) -> list[str]:
    """The comment lines before the diff (`git apply` and `patch` skip them)."""
    lines = _wrapped("robotdesc collision: swaps the <collision> elements in the xacro sources "
                     "for the generated ones; re-expanding the description then gives the "
                     "generated geometry.")
    if files:
        patch = _short(os.path.join(out_dir, patch_name), root)
        lines += [(f"Paths are relative to the root folder {_short(root, out_dir)} "
                   "(from this patch's folder)."),
                  f"Apply it there:  git apply {patch}",
                  f"            or:  patch -p1 < {patch}"]
        lines += _wrapped("Files: " + ", ".join(_short(f, root) for f in files))
        lines += _wrapped("Patched links: " + ", ".join(patched))
    else:
        lines.append("Nothing to patch: no link's <collision> could be swapped in the sources.")
    if literal:
        lines += _wrapped("Replaced text that used xacro expressions (the new text is literal: "
                          "right for this run's xacro arguments; positions from this patch's "
                          "folder): " + ", ".join(literal))
    if escaping:
        lines += _wrapped("Warning: the output folder is in no ROS package, so mesh paths are "
                          "relative and leave the package of "
                          + ", ".join(_short(f, out_dir) for f in escaping)
                          + " (lint M104); use an --out folder inside a ROS package for "
                          "package:// URIs.")
    current = [item.link for item in skipped if item.reason.startswith(UP_TO_DATE)]
    skipped = [item for item in skipped if not item.reason.startswith(UP_TO_DATE)]
    if current:
        lines += _wrapped("Up to date (they call this run's macros already, nothing to do): "
                          + ", ".join(current))
    if skipped:
        name = patch_name.replace(".patch", ".xacro")
        lines += _wrapped(f"Not patched (paste their macros from {name} by hand; positions "
                          "from this patch's folder):")
        by_reason: dict[str, list[str]] = {}
        for item in skipped:
            by_reason.setdefault(item.reason, []).append(item.link)
        for reason, names in by_reason.items():
            lines += _wrapped(f"{', '.join(names)}: {reason}", "  ", "    ")
    return ["# " + re.sub(r"[\r\n]", " ", line) + "\n" for line in lines] + ["\n"]


def _wrapped(text: str, first: str = "", rest: str = "") -> list[str]:
    """Comment text in lines of at most 96 characters (paths and names are not broken)."""
    return textwrap.wrap(re.sub(r"\s+", " ", text), 96, initial_indent=first,
                         subsequent_indent=rest, break_long_words=False,
                         break_on_hyphens=False)


def _short(path: str, start: str) -> str:
    return os.path.relpath(path, start).replace(os.sep, "/")


def _key(where: Provenance) -> tuple[str, int]:
    """An element's (file, line), as the source files are searched by."""
    return (where.span.path, where.span.line)
