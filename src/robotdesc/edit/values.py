"""An edit changes only values that change: numbers equal within a tolerance keep the text
they are written with (their precision included)."""

from __future__ import annotations

import math


def numbers(text: str | None) -> list[float] | None:
    """The whitespace-separated numbers of an attribute value, or None if one is not."""
    try:
        return [float(v) for v in (text or "").split()]
    except ValueError:
        return None


#: The relative tolerance of a value written to six significant digits (a suggestion).
SIX_DIGITS = 5e-6


def same_number(old: float, new: float, tolerance: float = 1e-9) -> bool:
    """Whether `old` is `new` within the relative `tolerance`."""
    return math.isclose(old, new, rel_tol=tolerance, abs_tol=1e-15)


def merged_value(old: str | None, new: str, *, tolerance: float = 1e-9) -> str | None:
    """The text to write for an attribute now `old` that should be `new`; None when `old`
    already is `new` (nothing to edit). Numbers of a vector that do not change keep their
    written text.

    Args:
        tolerance: relative; the rule's (SIX_DIGITS for a suggested `<inertial>`: an old
            number that rounds to the suggestion is not changed).
    """
    if old is None:
        return new
    left, right = numbers(old), numbers(new)
    if left is None or right is None or len(left) != len(right) or not right:
        return None if old == new else new
    old_tokens, new_tokens = old.split(), new.split()
    kept = [o if same_number(a, b, tolerance) else n
            for a, b, o, n in zip(left, right, old_tokens, new_tokens)]
    if kept == old_tokens:
        return None
    return " ".join(kept)
