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


def written_precision(token: str) -> float:
    """Half a unit of the last digit a number is written with ("0.0842292" -> 5e-8)."""
    mantissa, _, exponent = token.lower().partition("e")
    digits = len(mantissa.partition(".")[2]) if "." in mantissa else 0
    try:
        power = int(exponent) if exponent else 0
    except ValueError:
        return 0.0
    return 0.5 * 10.0 ** (power - digits)


def same_number(old: float, new: float, new_token: str, precise: bool) -> bool:
    """Whether `old` is `new` (written as `new_token`): within 1e-9 relative, or with
    `precise` False within the precision `new_token` is written with."""
    if math.isclose(old, new, rel_tol=1e-9, abs_tol=1e-15):
        return True
    return not precise and abs(old - new) <= written_precision(new_token) * (1 + 1e-9)


def merged_value(old: str | None, new: str, *, precise: bool = True) -> str | None:
    """The text to write for an attribute now `old` that should be `new`; None when `old`
    already is `new` (nothing to edit). Numbers of a vector that do not change keep their
    written text.

    Args:
        precise: False when `new` is a rounded suggestion (an `<inertial>` written to six
            digits): an old number that rounds to it is not changed.
    """
    if old is None:
        return new
    left, right = numbers(old), numbers(new)
    if left is None or right is None or len(left) != len(right) or not right:
        return None if old == new else new
    old_tokens, new_tokens = old.split(), new.split()
    kept = [o if same_number(a, b, n, precise) else n
            for a, b, o, n in zip(left, right, old_tokens, new_tokens)]
    if kept == old_tokens:
        return None
    return " ".join(kept)
