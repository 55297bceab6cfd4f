"""The report's layout: plot titles count what the plots draw, legends sit above the rows,
and (in headless Chromium, at 1400 px) no table is wider than its box."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from view.browser import dump_dom, require_chromium, screenshot

from robotdesc.report import html_plots

REPO = Path(__file__).resolve().parents[2]
ENGINEER = REPO / "robots/engineer_description/urdf/engineer.urdf.xacro"
#: Where the 1400 px screenshots are kept for a person to look at (default: the test's tmp).
SHOTS = os.environ.get("ROBOTDESC_SCREENSHOTS")

#: Appended to a copy of the page: records, on <body>, every table (or scroll box) wider
#: than its container or than the window, and every plot legend overlapping its axes.
MEASURE = """<script>
addEventListener("load", () => {
  const bad = [];
  const width = document.documentElement.clientWidth;
  for (const table of document.querySelectorAll("table")) {
    const box = table.parentElement, r = table.getBoundingClientRect();
    if (!table.offsetParent) continue;  // in a closed <details>
    if (r.right > width + 1 || table.scrollWidth > box.clientWidth + 1)
      bad.push({table: table.closest("section")?.id, right: r.right, width: table.scrollWidth,
                box: box.clientWidth});
  }
  for (const box of document.querySelectorAll(".scroll"))
    if (box.scrollWidth > box.clientWidth + 1)
      bad.push({scroll: box.closest("section")?.id, width: box.scrollWidth,
                box: box.clientWidth});
  document.body.setAttribute("data-overflow", JSON.stringify(bad));
  document.body.setAttribute("data-window", String(width));
});
</script>"""


def test_titles_count_the_links_drawn() -> None:
    pytest.importorskip("matplotlib")
    rows = [(f"l{i}", (1.0, 2.0, 3.0), (1.5, 2.0, 3.0)) for i in range(7)]
    rows[0] = ("l0 (+2 alike)", *rows[0][1:])
    svg = html_plots.moments_plot(rows, total=10)
    assert "Principal moments: 9 of the 10 links in the inertia table in 7 rows" in svg
    svg = html_plots.faces_plot([("a", 10, 2), ("b", 3, 1)], total=2)
    assert "Triangles per link: 2 links," in svg
    assert html_plots.links_drawn([("w (+99 alike)", 1, 1), ("b", 1, 1)]) == 101


def test_legend_is_above_the_axes() -> None:
    pytest.importorskip("matplotlib")
    from matplotlib.figure import Figure

    figure = Figure()
    axes = figure.subplots()
    axes.plot([1, 2], [1, 2], label="x")
    html_plots._legend_above(axes)
    figure.canvas.draw()
    legend = axes.get_legend().get_window_extent()
    assert legend.y0 >= axes.get_window_extent().y1 - 1


@pytest.mark.slow
def test_report_fits_1400_px_in_chromium(tmp_path: Path) -> None:
    require_chromium()
    page = tmp_path / "report.html"
    env = {**os.environ, "ROBOTDESC_CACHE_DIR": str(tmp_path / "cache"), "MPLBACKEND": "Agg"}
    done = subprocess.run([sys.executable, "-m", "robotdesc", "report", str(ENGINEER), "-o",
                           str(page), "-q"], capture_output=True, text=True, env=env,
                          timeout=900, check=False)
    assert done.returncode == 0, done.stderr
    text = page.read_text(encoding="utf-8")
    measured = tmp_path / "measured.html"
    measured.write_text(text.replace("</body>", MEASURE + "</body>"), encoding="utf-8")
    folder = Path(SHOTS) if SHOTS else tmp_path
    folder.mkdir(parents=True, exist_ok=True)
    pixels = screenshot(page, folder / "report-1400.png", (1400, 3000))
    assert pixels.shape[1] == 1400
    dom = dump_dom(measured, (1400, 1000))
    found = re.search(r'data-overflow="([^"]*)"', dom)
    assert found, "the measuring script did not run"
    overflow = json.loads(found.group(1).replace("&quot;", '"'))
    assert overflow == [], overflow
    assert re.search(r'data-window="1\d\d\d"', dom)
