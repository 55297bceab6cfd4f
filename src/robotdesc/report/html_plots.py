"""The plots of the HTML report, as inline SVG drawn with matplotlib (the `report` extra).

Pure functions of plain data: each returns an `<svg>` string, or None when there is nothing
to plot. Text stays text in the SVG (searchable, and smaller). matplotlib is imported inside
the functions; `plots_available()` tells whether it is installed.
"""

from __future__ import annotations

import io
import re
from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

Vec3 = tuple[float, float, float]

#: Most links one plot shows (the rest are summarised in its title).
MAX_ROWS = 40
DECLARED_COLOR = "#1f5fa8"
DERIVED_COLOR = "#d9731a"


def plots_available() -> bool:
    """matplotlib can be imported."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return False
    return True


def _figure(rows: int) -> tuple[Figure, Axes]:
    """A Figure without pyplot (no global backend or state is touched)."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(8.0, 1.3 + 0.24 * rows))
    return figure, figure.subplots()


def _svg(figure: Figure, salt: str) -> str:
    import matplotlib

    buffer = io.StringIO()
    with matplotlib.rc_context({"svg.fonttype": "none", "svg.hashsalt": salt}):
        figure.savefig(buffer, format="svg", bbox_inches="tight", metadata={"Date": None})
    text = buffer.getvalue()
    start = text.find("<svg")
    svg = text[start:] if start >= 0 else text
    return re.sub(r"<metadata>.*?</metadata>", "", svg, flags=re.DOTALL)


def moments_plot(rows: Sequence[tuple[str, Vec3, Vec3]], total: int | None = None
                 ) -> str | None:
    """Declared against mesh-derived principal moments, one line of the chart per link.

    Args:
        rows: (link, declared moments, derived moments) ascending, kg*m^2, worst first;
            at most MAX_ROWS are drawn.
        total: the number of links compared (for the title; default len(rows)).
    """
    shown = [r for r in rows if min(r[1]) > 0 and min(r[2]) > 0][:MAX_ROWS]
    if not shown:
        return None
    from matplotlib.collections import LineCollection

    figure, axes = _figure(len(shown))
    rows_y = [float(y) for y, _ in enumerate(shown) for _ in range(3)]  # one artist per kind
    declared = [d for _, moments, _ in shown for d in moments]
    derived = [g for _, _, moments in shown for g in moments]
    axes.add_collection(LineCollection([[(d, y), (g, y)] for d, g, y in
                                        zip(declared, derived, rows_y)],
                                       colors="#bbbbbb", linewidths=1, zorder=1))
    axes.scatter(declared, rows_y, color=DECLARED_COLOR, s=18, zorder=2, label="declared")
    axes.scatter(derived, rows_y, color=DERIVED_COLOR, marker="x", s=22, zorder=3,
                 label="from geometry, at the declared mass")
    axes.set_xscale("log")
    _plain_log_ticks(axes)
    axes.set_yticks(range(len(shown)), [r[0] for r in shown], fontsize=8)
    axes.invert_yaxis()
    axes.set_xlabel("principal moment of inertia (kg·m²)")
    axes.set_title(_title("Principal moments", shown, total, "in the inertia table")
                   + ", largest difference first", fontsize=10, pad=24)
    axes.grid(axis="x", which="major", color="#e4e4e4")
    _legend_above(axes)
    return _svg(figure, "moments")


def faces_plot(rows: Sequence[tuple[str, int, int]], total: int | None = None) -> str | None:
    """Polygon counts per link, visual against collision (log scale).

    Args:
        rows: (link, visual faces, collision faces), at most MAX_ROWS drawn in this order.
        total: the number of links with geometry (for the title; default len(rows)).
    """
    shown = [r for r in rows if r[1] > 0 or r[2] > 0][:MAX_ROWS]
    if not shown:
        return None
    figure, axes = _figure(len(shown))
    ys = range(len(shown))
    axes.barh([y - 0.2 for y in ys], [max(r[1], 0.8) for r in shown], height=0.4,
              color=DECLARED_COLOR, label="visual")
    axes.barh([y + 0.2 for y in ys], [max(r[2], 0.8) for r in shown], height=0.4,
              color=DERIVED_COLOR, label="collision")
    axes.set_xscale("log")
    _plain_log_ticks(axes)
    axes.set_yticks(list(ys), [r[0] for r in shown], fontsize=8)
    axes.invert_yaxis()
    axes.set_xlabel("triangles")
    axes.set_title(_title("Triangles per link", shown, total, "with geometry")
                   + ", most visual first", fontsize=10, pad=24)
    axes.grid(axis="x", which="major", color="#e4e4e4")
    _legend_above(axes)
    return _svg(figure, "faces")


_ALIKE = re.compile(r" \(\+(\d+) alike\)$")


def links_drawn(rows: Sequence[tuple[str, object, object]]) -> int:
    """The links the drawn rows stand for (a row "name (+N alike)" stands for N + 1)."""
    return sum(1 + int(found.group(1)) if (found := _ALIKE.search(row[0])) else 1
               for row in rows)


def _title(what: str, shown: Sequence[tuple[str, object, object]], total: int | None, kind: str) -> str:
    """"Principal moments of 7 links" or "... of 7 of the 10 links compared": the count
    is what the plot draws."""
    drawn = links_drawn(shown)
    rows = f" in {len(shown)} rows" if len(shown) != drawn else ""
    if total is None or total <= drawn:
        return f"{what}: {drawn} links{rows}"
    return f"{what}: {drawn} of the {total} links {kind}{rows}"


def _plain_log_ticks(axes: Axes) -> None:
    """Log-axis tick labels as plain numbers ("0.001", "1e+04"): matplotlib's default
    typesets each with mathtext, the slowest part of drawing these plots."""
    from matplotlib.ticker import FuncFormatter

    axes.xaxis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))


def _legend_above(axes: Axes) -> None:
    """The legend in one line above the plot, where it covers no row."""
    axes.legend(fontsize=8, loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=2,
                frameon=False, borderaxespad=0.2)
