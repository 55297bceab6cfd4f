"""Plain-text tables that fit a terminal width (100 columns by default): the widest
free-text column wraps onto more lines, and over-long cells of the other columns are
shortened in the middle ("left_main_…_link"), so that no column is hidden."""

from __future__ import annotations

import textwrap
from collections.abc import Sequence

#: Columns a terminal table may use.
WIDTH = 100
_GAP = "  "


def shorten(text: str, width: int) -> str:
    """`text` cut in the middle to `width` characters (marked with "…")."""
    if len(text) <= width or width < 3:
        return text[:max(width, 0)] if len(text) > width else text
    keep = width - 1
    return text[:(keep + 1) // 2] + "…" + text[len(text) - keep // 2:]


def render_table(header: Sequence[str], rows: Sequence[Sequence[str]], *, width: int = WIDTH,
                 wrap: int = -1, right: Sequence[int] = (), max_cell: int = 32) -> str:
    """The rows under the header, columns two spaces apart, every line at most `width`
    characters (ending with a newline).

    Args:
        header: the column names.
        rows: the cells, as text.
        width: the most characters per line.
        wrap: the column that wraps when the table is too wide (default: the last).
        right: columns aligned right (numbers).
        max_cell: the longest cell of the other columns when the table is too wide.
    """
    table = [list(header), *[list(row) for row in rows]]
    count = len(header)
    wrap = wrap % count
    widths = [max(len(row[i]) for row in table) for i in range(count)]
    if sum(widths) + len(_GAP) * (count - 1) > width:
        for i in range(count):
            if i != wrap and widths[i] > max_cell:
                for row in table:
                    row[i] = shorten(row[i], max_cell)
                widths[i] = max(len(row[i]) for row in table)
        others = sum(w for i, w in enumerate(widths) if i != wrap) + len(_GAP) * (count - 1)
        widths[wrap] = max(12, min(widths[wrap], width - others))
    lines = []
    for row in table:
        pieces = textwrap.wrap(row[wrap], widths[wrap]) or [""]
        for number, piece in enumerate(pieces):
            cells = [(piece if i == wrap else row[i] if number == 0 else "")
                     for i in range(count)]
            text = _GAP.join(cell.rjust(widths[i]) if i in right else cell.ljust(widths[i])
                             for i, cell in enumerate(cells))
            lines.append(text.rstrip())
    return "\n".join(lines) + "\n"
