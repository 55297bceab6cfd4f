"""Text that is safe to print in a terminal or a CI log.

Names and messages can carry text a description's author chose (a link name with `&#10;`,
a worker's message): a newline would give it a line of its own (a forged
`::error file=...::` workflow command in a GitHub Actions log), an escape sequence would
drive the reader's terminal. Reports show such characters as visible escapes instead.
"""

from __future__ import annotations

#: C0 controls but tab, DEL and C1 controls -> a visible escape ("\\n", "\\x1b", "\\x9b").
_NAMED = {0x0A: "\\n", 0x0D: "\\r"}
_ESCAPES = {code: _NAMED.get(code, f"\\x{code:02x}")
            for code in [*range(9), *range(10, 32), 127, *range(128, 160)]}


def printable(text: str) -> str:
    """`text` with every control character but tab shown as an escape (a newline as `\\n`),
    so that it stays on its line and sends the terminal nothing."""
    return text.translate(_ESCAPES)
