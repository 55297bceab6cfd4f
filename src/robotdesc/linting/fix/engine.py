"""Plan the fixes of lint results as byte edits of their source files, diff them, write them.

Writes are atomic (robotdesc.atomic), only to files inside the linted package, and refused
for a file whose bytes changed since it was read. Only the attribute values (or a new
attribute) change; every other byte of the file stays as it was.
"""

from __future__ import annotations

import dataclasses
import difflib
import hashlib
import logging
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

from robotdesc.atomic import write_atomically
from robotdesc.diagnostics import Diagnostic
from robotdesc.linting.fix.changes import (
    CaseHelper,
    ExpandedIndex,
    Fixer,
    NotApplicable,
    enclosing_package,
    fixer_for,
)
from robotdesc.linting.fix.plan import Edit, SourceCache, plan_change
from robotdesc.linting.result import LintResult
from robotdesc.rules.fixes import Applicability, fix_applicability

log = logging.getLogger(__name__)

FIXED, UNSAFE, NOT_APPLICABLE = "fixed", "unsafe", "not-applicable"


@dataclass(frozen=True)
class FixOutcome:
    """What became of one diagnostic's fix.

    Attributes:
        status: "fixed" (its edits are in the plan), "unsafe" (needs --unsafe-fixes) or
            "not-applicable" (`reason` says why, e.g. "computed at FILE:LINE").
        edits: the source edits of this diagnostic's fix.
    """

    diagnostic: Diagnostic
    applicability: Applicability
    status: str
    reason: str = ""
    edits: tuple[Edit, ...] = ()


@dataclass(frozen=True)
class FileFix:
    """One source file: its bytes as read, and as fixed."""

    path: str
    before: bytes
    after: bytes

    def diff(self, relative_to: str | None = None) -> str:
        base = os.path.abspath(relative_to or os.getcwd())
        name = os.path.relpath(self.path, base) if _inside(self.path, base) else self.path
        return "".join(difflib.unified_diff(
            self.before.decode("utf-8").splitlines(keepends=True),
            self.after.decode("utf-8").splitlines(keepends=True), f"a/{name}", f"b/{name}"))


@dataclass(frozen=True)
class FixPlan:
    """The fixes of a run: the files to write and the fate of each fixable finding."""

    files: tuple[FileFix, ...] = ()
    outcomes: tuple[FixOutcome, ...] = field(default=())

    def diff(self, relative_to: str | None = None) -> str:
        return "".join(f.diff(relative_to) for f in self.files)

    @property
    def fixed(self) -> tuple[FixOutcome, ...]:
        return tuple(o for o in self.outcomes if o.status == FIXED)

    @property
    def problems_fixed(self) -> int:
        """How many problems the plan fixes: findings whose edits are the same (one macro
        line fixed for every element and variant it made) count once."""
        return len({frozenset((e.path, e.start, e.end) for e in o.edits) for o in self.fixed})


class FileChanged(Exception):
    """A file changed on disk since it was read: its fixes are not written."""


def package_root(target: str) -> str:
    """The folder fixes may write in: the target's ROS package, else the target's folder."""
    found = enclosing_package(os.path.abspath(target))
    return found[1] if found else os.path.dirname(os.path.abspath(target))


def plan_fixes(results: Sequence[LintResult], *, unsafe: bool = False,
               helpers: Mapping[str, CaseHelper] | None = None) -> FixPlan:
    """Plan the fixes of every fixable diagnostic of `results` (LintResults with their
    expansion and model kept).

    Args:
        unsafe: plan unsafe fixes too.
        helpers: target -> M102's helper (the file on disk a mesh reference names).
    """
    outcomes: list[FixOutcome] = []
    caches: dict[str, SourceCache] = {}
    raw: dict[str, bytes] = {}
    indexes: list[ExpandedIndex] = []  # kept alive: edits name elements by id
    for result in results:
        if result.expanded is None:
            continue
        root = package_root(result.target)
        cache = caches.setdefault(root, SourceCache(_within(root)))
        index: ExpandedIndex | None = None
        for diagnostic in result.diagnostics:
            fixer = fixer_for(diagnostic)
            applicability = fix_applicability(diagnostic.code, diagnostic.fix)
            if fixer is None or applicability is None:
                continue
            if applicability is Applicability.UNSAFE and not unsafe:
                outcomes.append(FixOutcome(diagnostic, applicability, UNSAFE,
                                           "an unsafe fix (apply with --unsafe-fixes)"))
                continue
            if index is None:
                expanded = result.expanded
                index = ExpandedIndex(expanded.xml, expanded.source, tuple(expanded.files))
                indexes.append(index)
            helper = (helpers or {}).get(result.target)
            outcomes.append(_plan_one(diagnostic, applicability, fixer, index, cache, helper))
        for cache in caches.values():
            raw.update(cache.raw)
    outcomes = _check_shared(outcomes)
    return FixPlan(_apply(outcomes, raw), tuple(outcomes))


def _plan_one(diagnostic: Diagnostic, applicability: Applicability, fixer: Fixer,
              index: ExpandedIndex, cache: SourceCache, helper: CaseHelper | None
              ) -> FixOutcome:
    changes = fixer(diagnostic, index, helper)
    if isinstance(changes, NotApplicable):
        return FixOutcome(diagnostic, applicability, NOT_APPLICABLE, changes.reason)
    edits: list[Edit] = []
    for change in changes:
        edit = plan_change(change, index, cache)
        if isinstance(edit, NotApplicable):
            return FixOutcome(diagnostic, applicability, NOT_APPLICABLE, edit.reason)
        edits.append(dataclasses.replace(edit, target=id(change.element)))
    if not edits:
        return FixOutcome(diagnostic, applicability, NOT_APPLICABLE,
                          "the source already has the fixed values")
    return FixOutcome(diagnostic, applicability, FIXED, edits=tuple(edits))


def _check_shared(outcomes: list[FixOutcome]) -> list[FixOutcome]:
    """Refuse fixes whose edit location also makes elements the fixes do not cover, or that
    ask different texts of one location; repeated until no refusal removes coverage."""
    while True:
        by_location: dict[tuple[str, int, int], list[tuple[int, Edit]]] = {}
        for number, outcome in enumerate(outcomes):
            for edit in outcome.edits if outcome.status == FIXED else ():
                by_location.setdefault((edit.path, edit.start, edit.end), []).append(
                    (number, edit))
        refused: dict[int, str] = {}
        for (path, _, _), entries in by_location.items():
            edits = [edit for _, edit in entries]
            group: frozenset[int] = frozenset().union(*(e.group for e in edits))
            covered = frozenset(e.target for e in edits)
            sites: frozenset[tuple[str, int]] = frozenset().union(*(e.sites for e in edits))
            reason = ""
            if len({e.text for e in edits}) > 1:
                reason = f"fixes ask different values at {path}:{edits[0].line}"
            elif not group <= covered:
                reason = (f"the text at {path}:{edits[0].line} makes {len(group)} elements, "
                          f"of which {len(group & covered)} have this fix")
            elif max(e.uses for e in edits) > len(sites):
                reason = (f"the argument at {path}:{edits[0].line} is used in "
                          f"{max(e.uses for e in edits)} places of its macro, not only here")
            for number, _ in entries if reason else ():
                refused.setdefault(number, reason)
        if not refused:
            return outcomes
        outcomes = [FixOutcome(o.diagnostic, o.applicability, NOT_APPLICABLE, refused[n])
                    if n in refused else o for n, o in enumerate(outcomes)]


def _apply(outcomes: list[FixOutcome], raw: dict[str, bytes]) -> tuple[FileFix, ...]:
    per_file: dict[str, dict[tuple[int, int], str]] = {}
    for outcome in outcomes:
        for edit in outcome.edits if outcome.status == FIXED else ():
            per_file.setdefault(edit.path, {})[(edit.start, edit.end)] = edit.text
    files: list[FileFix] = []
    for path in sorted(per_file):
        text = raw[path].decode("utf-8")
        last = len(text) + 1
        for (start, end), new in sorted(per_file[path].items(), reverse=True):
            if end > last:
                log.warning("overlapping fixes in %s at offset %d: one skipped", path, start)
                continue
            text = text[:start] + new + text[end:]
            last = start
        after = text.encode("utf-8")
        if after != raw[path]:
            files.append(FileFix(path, raw[path], after))
    return tuple(files)


def write_fixes(plan: FixPlan) -> tuple[list[str], list[str]]:
    """Write the fixed files atomically; (written, refused because changed since read)."""
    written: list[str] = []
    refused: list[str] = []
    for item in plan.files:
        try:
            with open(item.path, "rb") as handle:
                current = handle.read()
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


def _within(root: str) -> Callable[[str], bool]:
    """Whether a path is inside `root` (symbolic links resolved)."""
    return lambda path: _inside(path, root)


def _inside(path: str, root: str) -> bool:
    try:
        real, base = os.path.realpath(path), os.path.realpath(root)
        return os.path.commonpath([real, base]) == base
    except ValueError:
        return False
