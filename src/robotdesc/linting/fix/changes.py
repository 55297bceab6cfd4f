"""What a finding's fix changes in the expanded description: attribute values of expanded
elements. Where the change goes in the xacro source is robotdesc.edit.locate's job.

Rules make their fixes as data where they find the problem (`Finding.changes`, or
`Finding.unfixable` saying why not); the inertia rules' `<inertial>` block is turned into
changes by robotdesc.inertia.patch, the same code as `inertia --write`. A fixer reads a
`Diagnostic` and returns the `AttributeChange`s, or a `Refused` saying why not.
"""

from __future__ import annotations

from collections.abc import Callable

from robotdesc.diagnostics import Diagnostic
from robotdesc.edit.index import AttributeChange, Changes, ExpandedIndex, Refused
from robotdesc.inertia.patch import inertial_changes as block_changes


def inertial_changes(diagnostic: Diagnostic, index: ExpandedIndex) -> Changes:
    """The attribute changes that turn the declared `<inertial>` into the suggested block
    (the same as `inertia --write`'s, robotdesc.inertia.patch)."""
    return block_changes(diagnostic.fix or "", index.element(diagnostic.element))


def requested_changes(diagnostic: Diagnostic, index: ExpandedIndex) -> Changes:
    """The changes the rule asked for with its finding (`Finding.changes`)."""
    found: list[AttributeChange] = []
    for change in diagnostic.changes:
        element = index.element(change.element)
        if element is None:
            return Refused(f"{change.element} is not in the expanded description")
        found.append(AttributeChange(element, change.attribute, change.value,
                                     tolerance=change.tolerance))
    return found


def refused_changes(diagnostic: Diagnostic, _: ExpandedIndex) -> Changes:
    """No changes: the rule said why its fix cannot be made (`Finding.unfixable`)."""
    return Refused(diagnostic.unfixable)


#: A fixer: the diagnostic and the expanded document -> the changes, or why not.
Fixer = Callable[[Diagnostic, ExpandedIndex], Changes]


def fixer_for(diagnostic: Diagnostic) -> Fixer | None:
    """The fixer of a diagnostic: the changes its rule asked for, the refusal it gave, or
    the inertial one for an `<inertial>` fix; None when it carries no fix."""
    if diagnostic.changes:
        return requested_changes
    if diagnostic.unfixable:
        return refused_changes
    if (diagnostic.fix or "").lstrip().startswith("<inertial"):
        return inertial_changes
    return None
