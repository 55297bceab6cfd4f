"""Reading a config file's text and parsing its TOML, with errors at the file and line."""

from __future__ import annotations

import re
from typing import Any

from robotdesc.errors import ConfigError
from robotdesc.source import Span

#: Deepest nesting of arrays and inline tables accepted in a config (tomllib recurses per
#: level; no robotdesc setting needs more than two).
MAX_TOML_DEPTH = 32

_TOML_TOKENS = re.compile(r'''"""(?:[^"\\]|\\.|"(?!""))*"""|\'\'\'.*?\'\'\'|"(?:[^"\\\n]|\\.)*"|'[^'\n]*'|#[^\n]*|[\[\]{}\n]''',
                          re.DOTALL)


def read_text(path: str) -> str:
    """The config file's text.

    Raises:
        ConfigError: it cannot be read or is not UTF-8.
    """
    try:
        with open(path, encoding="utf-8") as handle:
            return handle.read()
    except OSError as exc:
        raise ConfigError(f"cannot read config file: {exc.strerror}", Span(path)) from None
    except UnicodeDecodeError:
        raise ConfigError("config file is not UTF-8 text", Span(path)) from None


def parse_toml(text: str, path: str) -> dict[str, Any]:
    """The TOML document of `text` (read from `path`).

    Raises:
        ConfigError: invalid TOML or nesting deeper than MAX_TOML_DEPTH, at its line.
    """
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        import tomli as tomllib
    check_nesting(text, path)
    try:
        document: dict[str, Any] = tomllib.loads(text)
        return document
    except RecursionError:  # not reached after check_nesting; kept as a last guard
        raise ConfigError(f"invalid TOML: arrays or tables nested deeper than "
                          f"{MAX_TOML_DEPTH} levels", Span(path)) from None
    except tomllib.TOMLDecodeError as exc:
        found = re.search(r"\(at line (\d+), column (\d+)\)", str(exc))
        message = re.sub(r"\s*\(at (line \d+, column \d+|end of document)\)", "", str(exc))
        if found:
            span = Span(path, int(found.group(1)), int(found.group(2)))
        elif "end of document" in str(exc):
            span = Span(path, text.count("\n") + 1)
        else:
            span = Span(path)
        raise ConfigError(f"invalid TOML: {message}", span) from None


def check_nesting(text: str, path: str) -> None:
    """Refuse arrays or inline tables nested deeper than MAX_TOML_DEPTH, at their line
    (linear time; strings and comments are skipped).

    Raises:
        ConfigError: too deep.
    """
    depth, line = 0, 1
    for match in _TOML_TOKENS.finditer(text):
        token = match.group(0)
        if token in "[{":
            depth += 1
            if depth > MAX_TOML_DEPTH:
                raise ConfigError(f"invalid TOML: arrays or tables nested deeper than "
                                  f"{MAX_TOML_DEPTH} levels", Span(path, line))
        elif token in "]}":
            depth = max(0, depth - 1)
        line += token.count("\n")
