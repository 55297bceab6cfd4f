"""Where a key stands in a config file: `ConfigError`s that name its TOML line."""

from __future__ import annotations

import re

from robotdesc.errors import ConfigError
from robotdesc.source import Span


class Locator:
    """Builds `ConfigError`s that point at the line of a key, when it can be found.

    Args:
        path: the config file.
        text: its text (empty: messages name the file only).
        prefix: the table's dotted prefix in the file ("tool.robotdesc." or ""), for messages.
    """

    def __init__(self, path: str, text: str, prefix: str) -> None:
        self.path, self.lines, self.prefix = path, text.splitlines(), prefix

    def error(self, key: str, message: str) -> ConfigError:
        """An "invalid configuration" error at the line of `key` (line 0 when not found)."""
        return ConfigError(f"invalid configuration: {message}", Span(self.path, self.line(key)))

    def line(self, key: str) -> int:
        """The first line (1-based) where `key` (snake or kebab case) is set, opens a table
        or is quoted; 0 when none."""
        names = "|".join(re.escape(v) for v in dict.fromkeys((key, key.replace("_", "-"))))
        pattern = re.compile(rf"^\s*(\[+[^\]]*)?[\"']?({names})[\"']?\s*(=|\]|\.)")
        header = re.compile(rf"^\s*\[[^\]]*\b({names})\b")
        quoted = re.compile(rf"[\"']({names})[\"']")
        for regex in ((pattern, header), (quoted,)):
            for number, line in enumerate(self.lines, 1):
                if any(r.search(line) for r in regex):
                    return number
        return 0
