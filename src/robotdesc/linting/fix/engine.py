"""Plan the fixes of lint results as `Fix`es (robotdesc.edit), diff them, write them.

Each fixable finding gets a `Fix` built from the provenance its expansion recorded; the one
edit engine (robotdesc.edit.engine) resolves conflicts between fixes, applies them to the
files as read, and writes them atomically, refusing a file that changed since it was read.
Writes go only to files inside the linted package.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from dataclasses import dataclass, field

from robotdesc.diagnostics import Diagnostic
from robotdesc.edit.engine import FileChange, apply_fixes, resolve_conflicts, write_changes
from robotdesc.edit.fix import Applicability, Edit, Fix
from robotdesc.edit.index import ExpandedIndex
from robotdesc.edit.locate import SourceCache, changes_fix, package_folder
from robotdesc.linting.fix.changes import fixer_for
from robotdesc.linting.result import LintResult
from robotdesc.rules.fixes import fix_applicability

log = logging.getLogger(__name__)

FIXED, UNSAFE, NOT_APPLICABLE = "fixed", "unsafe", "not-applicable"

#: One source file as read and as fixed (the engine's `FileChange`).
FileFix = FileChange


@dataclass(frozen=True)
class FixOutcome:
    """What became of one diagnostic's fix.

    Attributes:
        fix: the fix as planned (its edits, or display-only with the reason).
        applicability: the rule's (safe or unsafe).
        status: "fixed" (its edits are in the plan), "unsafe" (needs --unsafe-fixes) or
            "not-applicable" (`reason` says why, e.g. "computed at urdf/arm.xacro:53").
    """

    diagnostic: Diagnostic
    applicability: Applicability
    status: str
    reason: str = ""
    fix: Fix = field(default_factory=Fix)

    @property
    def edits(self) -> tuple[Edit, ...]:
        return self.fix.edits if self.status == FIXED else ()


@dataclass(frozen=True)
class FixPlan:
    """The fixes of a run: the files to write and the fate of each fixable finding."""

    files: tuple[FileChange, ...] = ()
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


def package_root(target: str) -> str:
    """The folder fixes may write in: the target's ROS package, else the target's folder."""
    return package_folder(target)


def plan_fixes(results: Sequence[LintResult], *, unsafe: bool = False) -> FixPlan:
    """Plan the fixes of every fixable diagnostic of `results` (LintResults with their
    expansion and model kept).

    Args:
        unsafe: plan unsafe fixes too.
    """
    outcomes: list[FixOutcome] = []
    caches: dict[str, SourceCache] = {}
    indexes: list[ExpandedIndex] = []  # kept alive: edits name elements by id
    for result in results:
        if result.expanded is None:
            continue
        root = package_root(result.target)
        cache = caches.setdefault(root, SourceCache(root))
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
            fix = changes_fix(fixer(diagnostic, index), index, cache, applicability)
            outcomes.append(_outcome(diagnostic, applicability, fix))
    raw: dict[str, bytes] = {}
    for cache in caches.values():
        raw.update(cache.raw)
    fixes = resolve_conflicts([o.fix for o in outcomes])
    outcomes = [o if o.status != FIXED or fix.applicable
                else _outcome(o.diagnostic, o.applicability, fix)
                for o, fix in zip(outcomes, fixes)]
    return FixPlan(apply_fixes([o.fix for o in outcomes if o.status == FIXED], raw),
                   tuple(outcomes))


def _outcome(diagnostic: Diagnostic, applicability: Applicability, fix: Fix) -> FixOutcome:
    if fix.applicable:
        return FixOutcome(diagnostic, applicability, FIXED, fix=fix)
    return FixOutcome(diagnostic, applicability, NOT_APPLICABLE, fix.reason, fix)


def write_fixes(plan: FixPlan) -> tuple[list[str], list[str]]:
    """Write the fixed files atomically; (written, refused because changed since read)."""
    return write_changes(plan.files)

