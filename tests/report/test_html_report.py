"""The HTML report: its sections from a real lint of a small package, the command, and the
page in headless Chromium (canvas drawn, links and findings shown)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from view.browser import drawn_pixels, dump_dom, require_chromium, screenshot
from view.robots import write_demo_package

import robotdesc
from robotdesc.errors import UsageError
from robotdesc.linting.result import LintResult
from robotdesc.report import html as html_module
from robotdesc.report import html_plots
from robotdesc.report.html import _merge_alike, render_html_report
from robotdesc.report.html_data import collect_report

REPO = Path(__file__).resolve().parents[2]
ENGINEER = REPO / "robots/engineer_description/urdf/engineer.urdf.xacro"


@pytest.fixture(scope="module")
def report(tmp_path_factory: pytest.TempPathFactory) -> str:
    result = robotdesc.lint(str(write_demo_package(tmp_path_factory.mktemp("report"))))
    return render_html_report(collect_report(result, joint_values={"grip": 0.01}))


def _section(page: str, key: str) -> str:
    match = re.search(rf'<section id="{key}">(.*?)</section>', page, re.DOTALL)
    assert match, f"no {key} section"
    return match.group(1)


def test_findings_are_grouped_by_link(report: str) -> None:
    findings = _section(report, "findings")
    groups = dict(re.findall(r'<details open data-link="([^"]+)">(.*?)</details>', findings,
                             re.DOTALL))
    assert set(groups) == {"finger_left", "finger_right"}  # base's I106 is opt-in (info)
    assert "I204" in groups["finger_left"] and "inertia-impossible-for-geometry" in findings
    assert "missing.stl" in groups["finger_right"]
    assert re.search(r"<td>I204</td><td>inertia-impossible-for-geometry</td>", findings)


def test_inertia_table_compares_declared_and_geometry(report: str) -> None:
    inertia = _section(report, "inertia")
    rows = dict(re.findall(r"<tr(?: class=\"bad\")?><td>([^<]+)</td>(.*?)</tr>", inertia))
    assert set(rows) >= {"base", "arm", "finger_left"}
    assert '<tr class="bad"><td>finger_left</td>' in inertia  # 1 kg*m^2 on a 1 cm block
    assert '<tr><td>base</td>' in inertia


def test_collision_table_counts_triangles_per_link(report: str) -> None:
    collision = _section(report, "collision")
    assert re.search(r"<td>arm</td><td>block\.stl</td><td class=num>12</td>"
                     r"<td>cylinder radius=0\.03 length=0\.2</td><td class=num>96</td>",
                     collision)
    assert "48 visual and 108 collision triangles" in collision


def test_view_and_plots_are_inline(report: str) -> None:
    assert 'data-robotdesc-scene="robotdesc-view-data"' in _section(report, "view")
    plots = _section(report, "plots")
    if not html_plots.plots_available():
        pytest.skip("matplotlib is not installed")
    assert plots.count("<svg") == 2 and 'id="plot-moments"' in plots
    assert "finger_left" in plots  # text stays text in the SVG
    assert not re.search(r'(src|href)\s*=\s*["\']?(https?:)?//', report)


def test_without_matplotlib_the_report_says_how_to_get_plots(tmp_path: Path,
                                                            monkeypatch) -> None:
    monkeypatch.setattr(html_module, "plots_available", lambda: False)
    result = robotdesc.lint(str(write_demo_package(tmp_path)))
    page = render_html_report(collect_report(result, view=False))
    assert "pip install '.[report]'" in _section(page, "plots")
    assert "The 3D view was not included" in _section(page, "view")


def test_identical_rows_are_merged_for_the_plots() -> None:
    rows = [("w0", (1.0, 2.0, 2.0), (1.0, 2.0, 2.00001)), ("w1", (1.0, 2.0, 2.0), (1.0, 2.0, 2.0)),
            ("arm", (3.0, 4.0, 5.0), (3.0, 4.0, 6.0))]
    assert [r[0] for r in _merge_alike(rows)] == ["w0 (+1 alike)", "arm"]


def run(*args: str) -> subprocess.CompletedProcess:
    path = os.pathsep.join(filter(None, [str(REPO / "src"), os.environ.get("PYTHONPATH")]))
    return subprocess.run([sys.executable, "-m", "robotdesc", *args], capture_output=True, check=False,
                          text=True, env={**os.environ, "PYTHONPATH": path}, timeout=600)


def test_report_command_writes_the_page(tmp_path: Path) -> None:
    urdf = write_demo_package(tmp_path)
    out = tmp_path / "report.html"
    done = run("report", str(urdf), "-o", str(out), "--q", "shoulder=0.2")
    assert done.returncode == 0, done.stderr
    assert re.search(r"wrote .*report\.html \(\d\.\d\d MB, 2 findings", done.stderr)
    page = out.read_text(encoding="utf-8")
    assert page.startswith("<!DOCTYPE html>") and "demo: robotdesc report" in page
    bad = run("report", str(urdf), "-o", str(tmp_path / "x.html"), "--q", "grip_mirror=1")
    assert bad.returncode == 2 and "mimics 'grip'" in bad.stderr


@pytest.mark.slow
def test_report_with_generated_collision(tmp_path: Path) -> None:
    out = tmp_path / "report.html"
    done = run("report", str(write_demo_package(tmp_path)), "-o", str(out),
               "--collision", "hull", "--jobs", "2")
    assert done.returncode == 0, done.stderr
    collision = _section(out.read_text(encoding="utf-8"), "collision")
    assert "<h3>Generated collision geometry</h3>" in collision
    assert re.search(r"<td>arm</td><td>hull</td><td>ok</td>", collision)


@pytest.mark.slow
@pytest.mark.parametrize("target", ["demo", "engineer"])
def test_report_in_the_browser(tmp_path: Path, target: str) -> None:
    require_chromium()
    urdf = write_demo_package(tmp_path) if target == "demo" else ENGINEER
    page = tmp_path / "report.html"
    done = run("report", str(urdf), "-o", str(page))
    assert done.returncode == 0, done.stderr
    pixels = screenshot(page, tmp_path / "report.png", (1280, 1000))
    # the view sits below the heading: its canvas spans about y 200..760, x 30..960
    assert drawn_pixels(pixels[240:740, 40:900]) > 0.02, "the 3D view's canvas is blank"
    dom = dump_dom(page, (1280, 1000))
    assert 'data-status="ready"' in dom
    if target == "engineer":  # lint-clean: every link listed, none flagged
        assert 'data-link="left_flipper_link"' in dom and 'class="rd-finding"' not in dom
        return
    for link in ("finger_left", "finger_right"):
        assert re.search(rf'<li class="rd-finding" data-link="{link}"', dom)  # the viewer
        assert f'<details data-link="{link}"' in dom or \
            f'<details open="" data-link="{link}"' in dom  # the findings section


def test_plots_of_nothing_are_none_and_plots_are_plain_svg() -> None:
    pytest.importorskip("matplotlib")
    assert html_plots.moments_plot([("a", (0.0, 1.0, 1.0), (1.0, 1.0, 1.0))]) is None
    assert html_plots.faces_plot([("a", 0, 0)]) is None
    svg = html_plots.faces_plot([("arm", 1200, 12), ("base", 12, 0)], total=5)
    assert svg.startswith("<svg") and svg.rstrip().endswith("</svg>")
    assert "Triangles per link: 2 of the 5 links with geometry" in svg and ">arm<" in svg
    assert "<metadata>" not in svg and "xlink:href=\"http" not in svg


def test_collision_result_as_html() -> None:
    from robotdesc.collision import CollisionOptions, CollisionResult, LinkOutcome, LinkReport
    from robotdesc.collision.result import Finding
    from robotdesc.model.elements import Robot
    from robotdesc.report.html import collision_result_html

    report = LinkReport("head <link>", "hull", "warning", faces_before=1000, faces_after=100,
                        hulls=1, volume_ratio=1.5, forward_max=0.01, backward_max=0.02,
                        diagonal=0.5, findings=(Finding("over-limit", "warning", "too many"),))
    result = CollisionResult(Robot("r"), (LinkOutcome(report),), CollisionOptions(), 1.0)
    html = collision_result_html(result)
    assert "<td>head &lt;link&gt;</td><td>hull</td><td>warning</td>" in html
    assert "<td class=num>4.00%</td>" in html and "warning: too many" in html
    from robotdesc.report.notebook import html_of

    assert html_of(result) == html  # Jupyter shows the same table


def test_the_header_counts_rules_as_robotdesc_rules_lists_them(report: str) -> None:
    from robotdesc.rules.catalog import all_rules

    ran, total = map(int, re.search(r"(\d+) of (\d+) rules ran", report).groups())
    assert total == len(all_rules()) and 0 < ran < total  # opt-in rules did not run


def test_a_result_without_its_model_is_a_usage_error() -> None:
    with pytest.raises(UsageError, match="kept its model"):
        collect_report(LintResult("/ws/arm.urdf", ()), view=False)
