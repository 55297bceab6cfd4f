"""The one engine that writes fixes into the user's sources: `lint --fix/--diff`, `inertia
--write`, collision's xacro patch and the language server's code actions all go through it.

- conflicts: fixes that ask different texts of one location, overlap another fix's edit,
  change elements they do not cover (a literal shared by several elements) or a parameter or
  property used elsewhere too are refused (display-only, with the reason);
- the files are read once and edited by exact offsets; every other byte stays as it was;
- writes are atomic (robotdesc.atomic) and refused for a file that changed since it was read;
- idempotent: planning again on the fixed files gives no edits (values already equal are not
  rewritten, see robotdesc.edit.values).
"""

from __future__ import annotations

import difflib
import hashlib
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from robotdesc.atomic import write_atomically
from robotdesc.edit.fix import Edit, Fix
from robotdesc.edit.locate import inside, package_folder


@dataclass(frozen=True)
class FileChange:
    """One source file: its bytes as read, and as fixed."""

    path: str
    before: bytes
    after: bytes

    def diff(self, relative_to: str | None = None) -> str:
        """The unified diff, with `a/` and `b/` names relative to `relative_to` (default cwd)."""
        base = os.path.abspath(relative_to or os.getcwd())
        name = os.path.relpath(self.path, base) if inside(self.path, base) else self.path
        return unified_diff(name.replace(os.sep, "/"), self.before.decode("utf-8"),
                            self.after.decode("utf-8"))


def unified_diff(name: str, old: str, new: str) -> str:
    """A unified diff `patch -p1` and `git apply` take (lines split at LF, a missing final
    newline marked)."""
    out = []
    for line in difflib.unified_diff(_lines(old), _lines(new), f"a/{name}", f"b/{name}"):
        out.append(line if line.endswith("\n") else line + "\n\\ No newline at end of file\n")
    return "".join(out)


def _lines(text: str) -> list[str]:
    parts = text.split("\n")
    return [p + "\n" for p in parts[:-1]] + ([parts[-1]] if parts[-1] else [])


def resolve_conflicts(fixes: Sequence[Fix]) -> list[Fix]:
    """The fixes, with those that conflict turned display-only (the reason says where).

    Repeated until no refusal changes another fix's coverage."""
    fixes = list(fixes)
    while True:
        refused = _conflicts(fixes)
        if not refused:
            return fixes
        fixes = [Fix.refused(refused[n]) if n in refused else f for n, f in enumerate(fixes)]


def _conflicts(fixes: Sequence[Fix]) -> dict[int, str]:
    by_location: dict[tuple[str, int, int], list[tuple[int, Edit]]] = {}
    for number, fix in enumerate(fixes):
        for edit in fix.edits if fix.applicable else ():
            by_location.setdefault((edit.path, edit.start, edit.end), []).append((number, edit))
    refused: dict[int, str] = {}
    for (path, _, _), entries in by_location.items():
        edits = [edit for _, edit in entries]
        group: frozenset[int] = frozenset().union(*(e.group for e in edits))
        covered = frozenset(e.target for e in edits)
        sites: frozenset[tuple[str, int]] = frozenset().union(*(e.sites for e in edits))
        reason = ""
        if len({e.replacement for e in edits}) > 1:
            reason = "fixes ask different values at {where}"
        elif not group <= covered:
            reason = (f"the text at {{where}} makes {len(group)} elements, of which "
                      f"{len(group & covered)} have this fix")
        elif max(e.uses for e in edits) > len(sites):
            reason = (f"the value at {{where}} is used in {max(e.uses for e in edits)} "
                      "places, not only by these fixes")
        if reason:  # the package folder is looked up only for a refusal
            reason = reason.format(where=f"{package_relative(path)}:{edits[0].line}")
        for number, _ in entries if reason else ():
            refused.setdefault(number, reason)
    spans: dict[str, list[tuple[int, int, int]]] = {}
    for (path, start, end), entries in sorted(by_location.items()):
        spans.setdefault(path, []).extend((start, end, number) for number, _ in entries)
    for path, items in spans.items():
        reach, previous = -1, (-1, -1)
        for start, end, number in items:
            if (start, end) != previous and start < reach:
                refused.setdefault(number, "overlaps another fix's edit in "
                                           f"{package_relative(path)}")
            reach, previous = max(reach, end), (start, end)
    return refused


def package_relative(path: str) -> str:
    """A source file's name relative to its package (as fix reasons name files)."""
    root = package_folder(path)
    return os.path.relpath(path, root).replace(os.sep, "/") if inside(path, root) else path


def apply_fixes(fixes: Sequence[Fix], raw: Mapping[str, bytes]) -> tuple[FileChange, ...]:
    """The files the applicable fixes change (conflicts resolved first by the caller), with
    `raw` the bytes each file had when its edits were planned."""
    per_file: dict[str, dict[tuple[int, int], str]] = {}
    for fix in fixes:
        for edit in fix.edits if fix.applicable else ():
            per_file.setdefault(edit.path, {})[(edit.start, edit.end)] = edit.replacement
    return tuple(change for path in sorted(per_file)
                 if (change := apply_edits(path, raw[path], per_file[path])) is not None)


def apply_edits(path: str, before: bytes, edits: Mapping[tuple[int, int], str]
                ) -> FileChange | None:
    """One file with its edits (span -> replacement, none overlapping); None when unchanged."""
    text = before.decode("utf-8")
    for (start, end), new in sorted(edits.items(), reverse=True):
        text = text[:start] + new + text[end:]
    after = text.encode("utf-8")
    return FileChange(path, before, after) if after != before else None


def write_changes(changes: Sequence[FileChange]) -> tuple[list[str], list[str]]:
    """Write the changed files atomically; (written, refused because changed since read)."""
    written: list[str] = []
    refused: list[str] = []
    for item in changes:
        try:
            with open(item.path, "rb") as handle:
                current: bytes | None = handle.read()
        except OSError:
            current = None
        if current is None or _digest(current) != _digest(item.before):
            refused.append(item.path)
            continue
        write_atomically(item.path, item.after, durable=True)
        written.append(item.path)
    return written, refused


def _digest(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()
