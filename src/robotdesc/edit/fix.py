"""A fix as data: the byte-exact edits of source files that repair one finding, how sure the
fix is, and why it cannot be applied when it cannot.

Offsets are into the file's text decoded as UTF-8 (characters, not bytes): the planner reads
every file it edits as UTF-8 and the engine writes it back the same way.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass


class Applicability(str, enum.Enum):
    """How sure a fix is: `--fix` applies SAFE ones, `--unsafe-fixes` UNSAFE ones too, and a
    DISPLAY_ONLY fix is shown (with its reason) but never applied."""

    SAFE = "safe"
    UNSAFE = "unsafe"
    DISPLAY_ONLY = "display-only"

    def __str__(self) -> str:
        return self.value


@dataclass(frozen=True)
class Edit:
    """Replace `text[start:end]` of the source file `path` by `replacement`.

    Attributes:
        line: the 1-based line of the start tag (or property) the edit is in, for messages.
        group: the expanded elements (their ids) the edited text makes; the engine refuses an
            edit that changes elements no fix asked to change.
        sites: for an argument or a property, the `${name}` uses that lead to it.
        uses: for an argument or a property, how many uses its name has in all.
        target: the expanded element (its id) the change asked for.
    """

    path: str
    start: int
    end: int
    replacement: str
    line: int = 0
    group: frozenset[int] = frozenset()
    sites: frozenset[tuple[str, int]] = frozenset()
    uses: int = 0
    target: int = 0

    @property
    def text(self) -> str:
        """The replacement (the name the planner's callers used)."""
        return self.replacement


@dataclass(frozen=True)
class Fix:
    """The edits that repair one finding.

    Attributes:
        edits: source edits, applied together or not at all.
        applicability: SAFE, UNSAFE, or DISPLAY_ONLY (then `reason` says why, naming the
            source FILE:LINE relative to the package, e.g. "computed at urdf/arm.xacro:53").
        reason: why the fix cannot be applied ("" when it can).
    """

    edits: tuple[Edit, ...] = ()
    applicability: Applicability = Applicability.SAFE
    reason: str = ""

    @property
    def applicable(self) -> bool:
        return self.applicability is not Applicability.DISPLAY_ONLY and bool(self.edits)

    @classmethod
    def refused(cls, reason: str) -> "Fix":
        """A display-only fix: nothing to apply, and why."""
        return cls((), Applicability.DISPLAY_ONLY, reason)
