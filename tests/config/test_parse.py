"""A config file's text and TOML: unreadable, not UTF-8, invalid or too deep, at its line."""

from __future__ import annotations

from pathlib import Path

import pytest

from robotdesc.config import MAX_TOML_DEPTH, load_config
from robotdesc.config.parse import check_nesting, parse_toml, read_text
from robotdesc.errors import ConfigError


def test_invalid_toml_names_its_line_and_column() -> None:
    with pytest.raises(ConfigError, match="invalid TOML") as caught:
        parse_toml('select = ["J"]\nignore = [1,,]\n', "robotdesc.toml")
    assert caught.value.span.line == 2 and caught.value.span.col > 0


def test_nesting_too_deep_is_refused_at_its_line() -> None:
    text = "a = 1\nb = " + "[" * (MAX_TOML_DEPTH + 1) + "]" * (MAX_TOML_DEPTH + 1) + "\n"
    with pytest.raises(ConfigError, match="nested deeper than") as caught:
        check_nesting(text, "robotdesc.toml")
    assert caught.value.span.line == 2


def test_brackets_in_strings_and_comments_do_not_count() -> None:
    text = 'a = "' + "[" * 100 + '"\n# ' + "{" * 100 + "\nb = '''" + "[" * 100 + "'''\n"
    check_nesting(text, "robotdesc.toml")
    assert parse_toml(text, "robotdesc.toml")["a"] == "[" * 100


def test_unreadable_or_binary_file_names_the_file(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match="cannot read config file") as caught:
        read_text(str(tmp_path / "missing.toml"))
    assert caught.value.span.path == str(tmp_path / "missing.toml")
    binary = tmp_path / "robotdesc.toml"
    binary.write_bytes(b"select = ['\xff']\n")
    with pytest.raises(ConfigError, match="not UTF-8"):
        load_config(str(binary))
