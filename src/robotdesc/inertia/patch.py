"""The edits that put suggested `<inertial>` blocks into the xacro/URDF sources, through the
one edit engine (robotdesc.edit): `inertia --write` diffs them, `lint --fix --unsafe-fixes`
writes the same edits for the inertia rules' findings.

A declared `<inertial>` is changed attribute by attribute where its values are written (the
literal, in a macro body when every call gets the same value, the call site's argument, or
the one property that carries it); a number equal to the suggestion within the six digits the
suggestion is written with keeps its text. A link without an `<inertial>` gets the block
after its start tag. What cannot be written is listed with the reason.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from lxml import etree

from robotdesc.edit.engine import apply_fixes, resolve_conflicts
from robotdesc.edit.fix import Applicability, Edit, Fix
from robotdesc.edit.index import AttributeChange, Changes, ExpandedIndex, Refused, local
from robotdesc.edit.locate import SourceCache, changes_fix
from robotdesc.edit.source_text import line_indent
from robotdesc.edit.values import SIX_DIGITS, merged_value
from robotdesc.inertia.suggest import Suggestion

_INERTIA_ATTRIBUTES = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
_DEFAULTS = {("origin", "xyz"): "0 0 0", ("origin", "rpy"): "0 0 0"}


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


def inertial_changes(block: str, declared: etree._Element | None) -> Changes:
    """The attribute changes that turn a declared `<inertial>` (expanded element) into the
    suggested `block`; numbers compared within the block's written precision."""
    try:
        wanted_root = etree.fromstring(block)
    except etree.XMLSyntaxError:
        return Refused("the suggested <inertial> is not XML")
    if declared is None or local(declared.tag) != "inertial":
        return Refused("the declared <inertial> was not found")
    changes: list[AttributeChange] = []
    for wanted in wanted_root.iterchildren(etree.Element):
        tag = local(wanted.tag)
        have = next(iter(declared.iterchildren(tag)), None)
        names = _INERTIA_ATTRIBUTES if tag == "inertia" else tuple(wanted.attrib)
        for name in names:
            value = wanted.get(name, "0")
            if have is None:
                default = _DEFAULTS.get((tag, name))
                if default is None or _differs(default, value):
                    return Refused(f"the declared <inertial> has no <{tag}> to edit")
                continue
            current = have.get(name, _DEFAULTS.get((tag, name)))
            if current is None or _differs(current, value):
                changes.append(AttributeChange(have, name, value, tolerance=SIX_DIGITS))
    return changes


def _differs(old: str, new: str) -> bool:
    return merged_value(old, new, tolerance=SIX_DIGITS) is not None


def suggestion_fix(item: Suggestion, index: ExpandedIndex, files: SourceCache) -> Fix:
    """The edits that write one suggestion (unsafe: it changes what the robot is)."""
    declared = index.element(f"link:{item.link}/inertial")
    if declared is None:
        link = index.element(f"link:{item.link}")
        if link is None:
            return Fix.refused(f"link '{item.link}' is not in the expanded description")
        found = insert_child(link, item.block, index, files)
        if isinstance(found, Refused):
            return Fix.refused(found.reason)
        return Fix((found,), Applicability.UNSAFE)
    return changes_fix(inertial_changes(item.block, declared), index, files,
                       Applicability.UNSAFE)


def insert_child(parent: etree._Element, block: str, index: ExpandedIndex,
                 files: SourceCache) -> Edit | Refused:
    """Insert `block` (an element's text) as the first child of the literal start tag that
    made `parent` (a self-closing tag is opened and closed)."""
    span = index.where(parent).span
    source = files.get(span.path)
    if isinstance(source, str):
        return Refused(source)
    name = local(parent.tag)
    tags = source.at_line(span.line, name)
    if len(tags) != 1:
        return Refused(f"no single <{name}> written at {files.at(span.path, span.line)}")
    tag = tags[0]
    group = frozenset(id(e) for e in index.by_span.get((span.path, span.line, name), []))
    newline = "\r\n" if "\r\n" in source.text else "\n"
    indent = line_indent(source.text, tag.start)
    inner = newline.join(indent + "  " + line for line in block.splitlines())
    if tag.element_end == tag.end:  # <link .../>
        text = f">{newline}{inner}{newline}{indent}</{tag.name}>"
        return Edit(source.path, tag.close, tag.end, text, tag.line, group, target=id(parent))
    return Edit(source.path, tag.end, tag.end, newline + inner, tag.line, group,
                target=id(parent))


def build_patch(suggestions: Iterable[Suggestion], index: ExpandedIndex, files: SourceCache,
                relative_to: str | None = None) -> Patch:
    """The unified diff of every suggestion's edits (the sources are not written).

    Args:
        index: the expanded description the suggestions were made for.
        files: the sources (read once; edits go only inside its package).
        relative_to: directory the diff's file names are relative to (default: cwd).
    """
    items = list(suggestions)
    fixes = resolve_conflicts([suggestion_fix(item, index, files) for item in items])
    changed: list[tuple[str, str]] = []
    skipped: list[tuple[str, str]] = []
    for item, fix in zip(items, fixes):
        if fix.applicable:
            changed += [(edit.path, item.link) for edit in fix.edits[:1]]
        else:
            skipped.append((item.link, fix.reason))
    diff = "".join(change.diff(relative_to) for change in apply_fixes(fixes, files.raw))
    return Patch(diff, tuple(changed), tuple(skipped))
