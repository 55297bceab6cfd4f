"""Left/right name pairs: `left_arm`/`right_arm`, `l_hip`/`r_hip`, `knee_l`/`knee_r`."""

from __future__ import annotations

import re
from collections.abc import Iterable

_WORDS = (("left", "right"), ("Left", "Right"), ("LEFT", "RIGHT"))
#: A lone side letter as its own `_`/`-`/`.`-separated token.
_LETTER = re.compile(r"(?:(?<=^)|(?<=[_\-.]))([lLrR])(?=[_\-.]|$)")
_SWAP = {"l": "r", "r": "l", "L": "R", "R": "L"}


def mirrored_name(name: str) -> str | None:
    """The other side's name, or None when `name` names no side.

    The words left/right are swapped wherever they appear (in any of three cases); otherwise
    a lone side letter token (`l_`, `_r`, `_L_`) is swapped. Names mentioning both sides are
    not paired.
    """
    for left, right in _WORDS:
        if (left in name) != (right in name):
            return name.replace(left, right) if left in name else name.replace(right, left)
    lower = name.lower()
    if "left" in lower or "right" in lower:
        return None
    letters = _LETTER.findall(name)
    if len(letters) != 1:
        return None
    return _LETTER.sub(lambda m: _SWAP[m.group(1)], name, count=1)


def mirror_pairs(names: Iterable[str]) -> list[tuple[str, str]]:
    """Pairs (left-ish, right-ish) of names that both exist, each pair once, sorted."""
    known = set(names)
    pairs: set[tuple[str, str]] = set()
    for name in known:
        other = mirrored_name(name)
        if other is not None and other in known and other != name:
            pairs.add((min(name, other), max(name, other)))
    return sorted(pairs)
