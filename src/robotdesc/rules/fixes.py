"""Which rules' findings `robotdesc lint --fix` can write back, and whether the fix is safe.

A safe fix keeps the description's meaning (the same file under its right name, the same axis
direction at unit length, a path through the package to the same file) and is applied by
`--fix`; an unsafe fix changes what the robot is (its inertia, its limits, its mesh's size)
and needs `--unsafe-fixes` as well. The edits are planned and applied by robotdesc.edit.
"""

from __future__ import annotations

from robotdesc.edit.fix import Applicability

__all__ = ["FIXABLE", "Applicability", "fix_applicability"]

#: Rule code -> the applicability of its fix (a code absent here has no automatic fix).
FIXABLE: dict[str, Applicability] = {
    "I201": Applicability.UNSAFE,  # the <inertial> computed from the geometry
    "I202": Applicability.UNSAFE,
    "I204": Applicability.UNSAFE,
    "J103": Applicability.UNSAFE,  # swapped limits (one may have the wrong sign instead)
    "J107": Applicability.SAFE,    # the same axis at unit length
    "M102": Applicability.SAFE,    # the file that exists, under its own case
    "M108": Applicability.UNSAFE,  # scale 0.001: a heuristic judgement of units
    "P101": Applicability.SAFE,    # absolute path -> package:// (the same file)
    "P102": Applicability.SAFE,    # file:// URI -> package:// (the same file)
}


def fix_applicability(code: str, fix_text: str | None = None) -> Applicability | None:
    """The applicability of a rule's fix; a finding whose fix is an `<inertial>` block (the
    inertia rules') is unsafe even when its code is not listed."""
    found = FIXABLE.get(code)
    if found is None and fix_text and fix_text.lstrip().startswith("<inertial"):
        return Applicability.UNSAFE
    return found
