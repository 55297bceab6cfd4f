"""A TOML value against a type hint: lists become tuples, integers floats; wrong types refused."""

from __future__ import annotations

import enum
from typing import Any, Literal

import pytest

from robotdesc.config.coerce import coerce, describe
from robotdesc.diagnostics import Severity


class Colour(enum.Enum):
    RED = "red"
    BLUE = "blue"


@pytest.mark.parametrize("value, hint, expected", [
    (3, float, 3.0),
    (2, int, 2),
    (True, bool, True),
    ("x", str, "x"),
    (["a", "b"], tuple[str, ...], ("a", "b")),
    ([1, 2.5], tuple[float, float], (1.0, 2.5)),
    ([1, 2], list[float], [1.0, 2.0]),
    (None, float | None, None),
    (4, float | None, 4.0),
    ("slow", Literal["fast", "slow"], "slow"),
    ("red", Colour, Colour.RED),
    ("blue", Colour, Colour.BLUE),
    ("BLUE", Colour, Colour.BLUE),
    ("warning", Severity, Severity.WARNING),
    ({"k": 1}, Any, {"k": 1}),
])
def test_accepted_values_are_converted(value: object, hint: object, expected: object) -> None:
    result = coerce(value, hint)
    assert result == expected and type(result) is type(expected)


@pytest.mark.parametrize("value, hint, error, fragment", [
    (True, int, TypeError, "expected an integer"),
    (True, float, TypeError, "expected a number"),
    ("3", int, TypeError, "expected an integer"),
    (1, bool, TypeError, "expected true or false"),
    (1, str, TypeError, "expected a string"),
    ("a", tuple[str, ...], TypeError, "expected a list"),
    ([1.0], tuple[float, float], ValueError, "expected 2 values, got 1"),
    ("medium", Literal["fast", "slow"], ValueError, "expected one of 'fast', 'slow'"),
    ("x", float | None, TypeError, "expected float | None"),
    ("green", Colour, ValueError, "expected one of 'red', 'blue', got 'green'"),
    ("fatal", Severity, ValueError, "expected one of 'info', 'warning', 'error'"),
])
def test_wrong_values_are_refused(value: object, hint: object, error: type[Exception],
                                  fragment: str) -> None:
    with pytest.raises(error, match=fragment):
        coerce(value, hint)


def test_describe_names_a_type_in_plain_words() -> None:
    assert describe(int) == "int"
    assert describe(float | None) == "float | None"
