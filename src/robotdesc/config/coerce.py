"""A TOML value checked against a type hint of an options dataclass (rule options, meshes)."""

from __future__ import annotations

import enum
import types
import typing
from typing import Any


def coerce(value: Any, hint: Any) -> Any:
    """Check a TOML value against a type hint; convert lists to tuples and ints to floats.

    Raises:
        TypeError: the value has the wrong type.
        ValueError: the value has the right type but is not allowed (a Literal, a length).
    """
    origin = typing.get_origin(hint)
    if hint is Any:
        return value
    if origin in (typing.Union, types.UnionType):
        if value is None and type(None) in typing.get_args(hint):
            return None
        for option in typing.get_args(hint):
            if option is type(None):
                continue
            try:
                return coerce(value, option)
            except (TypeError, ValueError):
                continue
        raise TypeError(f"expected {describe(hint)}, got {value!r}")
    if origin is typing.Literal:
        if value not in typing.get_args(hint):
            raise ValueError(f"expected one of {', '.join(map(repr, typing.get_args(hint)))}, "
                             f"got {value!r}")
        return value
    if origin in (tuple, list, frozenset, set):
        return _sequence(value, origin, typing.get_args(hint))
    return _scalar(value, hint)


def describe(hint: Any) -> str:
    """A type hint in a user's words ("int", "float | None")."""
    name = getattr(hint, "__name__", None)
    return name if isinstance(name, str) and name else str(hint).replace("typing.", "")


def _sequence(value: Any, origin: Any, args: tuple[Any, ...]) -> Any:
    """A TOML array as a tuple, list, set or frozenset of coerced items."""
    if not isinstance(value, list):
        raise TypeError(f"expected a list, got {value!r}")
    if origin is tuple and args and args[-1] is not Ellipsis:
        if len(args) != len(value):
            raise ValueError(f"expected {len(args)} values, got {len(value)}")
        return tuple(coerce(v, a) for v, a in zip(value, args, strict=True))
    item = args[0] if args else Any
    return origin(coerce(v, item) for v in value)


def _scalar(value: Any, hint: Any) -> Any:
    """A TOML bool, integer, number, string or enum value checked against `hint`."""
    if hint is bool:
        if not isinstance(value, bool):
            raise TypeError(f"expected true or false, got {value!r}")
        return value
    if hint is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise TypeError(f"expected an integer, got {value!r}")
        return value
    if hint is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise TypeError(f"expected a number, got {value!r}")
        return float(value)
    if hint is str:
        if not isinstance(value, str):
            raise TypeError(f"expected a string, got {value!r}")
        return value
    if isinstance(hint, type) and issubclass(hint, enum.Enum):
        try:
            return hint(value)
        except ValueError:
            pass
        by_name = {member.name.lower(): member for member in hint}
        found = by_name.get(str(value).lower())
        if found is None:
            allowed = ", ".join(repr(member.value if isinstance(member.value, str)
                                     else member.name.lower()) for member in hint)
            raise ValueError(f"expected one of {allowed}, got {value!r}")
        return found
    if isinstance(hint, type) and not isinstance(value, hint):
        raise TypeError(f"expected {describe(hint)}, got {value!r}")
    return value
