"""Which rules run: `select` / `ignore` selectors, resolved by specificity (like ruff).

A selector is "ALL", a code prefix ("J", "J1", "J101", case-insensitive) or a rule name
("revolute-without-limit"). For each rule the most specific matching selector decides; on a
tie `ignore` wins. So `select = ["J"]` with `ignore = ["J1"]` runs J2xx only, and
`ignore = ["J"]` with `select = ["J101"]` still runs J101.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Protocol

from robotdesc.errors import UsageError

if TYPE_CHECKING:
    from robotdesc.rules.registry import Rule


class Named(Protocol):
    """What a selector is matched against: a rule's code and kebab-case name (a `Rule`, or
    a row of the rule index, `robotdesc.rules.index.known_names`)."""

    @property
    def code(self) -> str: ...

    @property
    def name(self) -> str: ...

_EXACT = 1000  # specificity of a full code or a rule name


def specificity(selector: str, code: str, name: str) -> int:
    """How specifically `selector` matches the rule (0: it does not match)."""
    text = selector.strip()
    if text.upper() == "ALL":
        return 1
    if text == name or text.upper() == code:
        return _EXACT
    if code.startswith(text.upper()) and text:
        return 1 + len(text)
    return 0


def best_match(selectors: Iterable[str], code: str, name: str) -> int:
    """The highest specificity among `selectors` for the rule (0: none matches)."""
    return max((specificity(s, code, name) for s in selectors), default=0)


def is_selected(code: str, name: str, select: Sequence[str] | None,
                ignore: Sequence[str] = ()) -> bool:
    """Whether a rule runs under these selectors (`select=None` means all rules)."""
    chosen = best_match(select if select is not None else ("ALL",), code, name)
    return chosen > 0 and chosen > best_match(ignore, code, name)


def select_rules(rules: Iterable[Rule], select: Sequence[str] | None,
                 ignore: Sequence[str] = ()) -> list[Rule]:
    """The rules that run, in their given order.

    An opt-in rule (`opt_in` true) runs only when a selector given in `select` selects it:
    its code, a prefix, its name, or "ALL" (which selects every rule). With no `select`
    (None: the defaults) it does not run.
    """
    return [r for r in rules if is_selected(r.code, r.name, select, ignore)
            and (not r.opt_in or best_match(select or (), r.code, r.name) > 0)]


def unknown_selectors(selectors: Iterable[str], rules: Iterable[Named]) -> list[str]:
    """The selectors that match none of `rules` ("ALL" always matches)."""
    known = list(rules)
    return [s for s in selectors
            if s.strip().upper() != "ALL" and not any(specificity(s, r.code, r.name)
                                                      for r in known)]


def check_selectors(selectors: Iterable[str], rules: Iterable[Named], flag: str) -> None:
    """Refuse a selector that matches none of `rules`, naming the option it came from.

    Raises:
        UsageError: the first selector that matches no rule.
    """
    unknown = unknown_selectors(selectors, rules)
    if unknown:
        raise UsageError(f"{flag}: no rule matches '{unknown[0]}' (see `robotdesc rules`)")


def find_rule(rules: Iterable[Rule], code_or_name: str) -> Rule | None:
    """The rule among `rules` with this code (case-insensitive) or name, or None."""
    key = code_or_name.strip()
    return next((r for r in rules if r.code == key.upper() or r.name == key), None)
