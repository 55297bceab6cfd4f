"""A key's TOML line: set, opening a table, or quoted; snake or kebab case; 0 when absent."""

from __future__ import annotations

import pytest

from robotdesc.config.locate import Locator

TEXT = """\
[tool.robotdesc]
select = ["J"]
fail-on = "warning"
[tool.robotdesc.rules.X101]
max_depth = 8
[tool.robotdesc.per-file-ignores]
"vendor/*.xacro" = ["Q9"]
"""


@pytest.mark.parametrize("key, line", [
    ("select", 2),
    ("fail_on", 3),         # the snake-case key finds the kebab-case spelling
    ("X101", 4),            # a table header
    ("max_depth", 5),
    ("per_file_ignores", 6),
    ("Q9", 7),              # only quoted: found by the second pass
    ("missing", 0),
])
def test_line_of_a_key(key: str, line: int) -> None:
    assert Locator("robotdesc.toml", TEXT, "").line(key) == line


def test_error_names_the_file_and_line() -> None:
    error = Locator("/p/pyproject.toml", TEXT, "tool.robotdesc.").error("max_depth", "bad")
    assert error.message == "invalid configuration: bad"
    assert (error.span.path, error.span.line) == ("/p/pyproject.toml", 5)
