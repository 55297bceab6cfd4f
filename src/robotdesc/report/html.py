"""The HTML report: one self-contained page with the findings grouped by link, the 3D view,
the inertia table, the collision table and plots (inline SVG). No network needed to open it.

`render_html_report(data)` is a pure function of `ReportData` (see html_data.py).
"""

from __future__ import annotations

import html
import math
import os
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, TypeVar

from robotdesc._version import __version__
from robotdesc.diagnostics import Diagnostic
from robotdesc.report.html_data import ReportData
from robotdesc.report.html_plots import faces_plot, moments_plot, plots_available
from robotdesc.rules.catalog import all_rules
from robotdesc.view.findings import findings_by_link
from robotdesc.view.html import view_fragment

if TYPE_CHECKING:
    from robotdesc.collision.result import CollisionResult
    from robotdesc.inertia.table import InertiaRow

STYLE = """
body{font:14px/1.45 system-ui,sans-serif;color:#1d1f24;margin:0;background:#fafbfc}
main{max-width:1360px;margin:0 auto;padding:16px 20px 48px;box-sizing:border-box}
h1{font-size:22px;margin:8px 0 2px}h2{font-size:18px;margin:28px 0 8px;border-bottom:1px solid #dde}
.meta{color:#556;margin:0 0 8px}.counts span{display:inline-block;margin-right:12px}
nav a{margin-right:12px}
table{border-collapse:collapse;margin:6px 0;font-size:13px;background:#fff;max-width:100%}
th,td{border:1px solid #dde;padding:3px 7px;text-align:left;vertical-align:top;
overflow-wrap:anywhere;min-width:4.5em}
td:first-child{min-width:12em}
th{background:#f0f2f6;position:sticky;top:0}
td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
td.vec{text-align:right;font-variant-numeric:tabular-nums;overflow-wrap:normal;min-width:7em}
td.where{font-size:12px;min-width:12em}
.scroll{max-height:640px;overflow-y:auto;overflow-x:auto;display:block;max-width:100%}
.scroll table{width:100%}
.sev-error{color:#b3261e;font-weight:600}.sev-warning{color:#9a5b00;font-weight:600}
.sev-info{color:#33669a}
tr.bad td{background:#fff1ef}
details{margin:4px 0;background:#fff;border:1px solid #e3e5ea;border-radius:4px}
summary{cursor:pointer;padding:4px 8px}summary .n{color:#b3261e;font-weight:600}
details table{margin:4px 8px 8px}
pre{margin:2px 0;font-size:12px;background:#f5f6f8;padding:4px;overflow:auto;max-width:700px;
white-space:pre-wrap;overflow-wrap:anywhere}
.plot svg{max-width:100%;height:auto}.note{color:#556}
.empty{color:#2e7d32}.codes{color:#667;font-size:12px;margin-left:6px}
.groups{max-height:640px;overflow:auto;border:1px solid #e3e5ea;padding:4px;background:#fff}
"""


def _e(value: object) -> str:
    return html.escape(str(value), quote=True)


def _num(value: float | None, digits: int = 4) -> str:
    return "-" if value is None else f"{value:.{digits}g}"


def _vec(values: Sequence[float] | None) -> str:
    return "-" if values is None else " ".join(f"{v:.4g}" for v in values)


def _location(diagnostic: Diagnostic) -> str:
    return str(diagnostic.where.span) if diagnostic.where is not None else ""


def _table(head: Sequence[str], rows: Iterable[str], scroll: bool = False) -> str:
    """A table; `scroll` puts it in a box of bounded height (long tables)."""
    cells = "".join(f"<th>{_e(h)}</th>" for h in head)
    table = f"<table><thead><tr>{cells}</tr></thead><tbody>{''.join(rows)}</tbody></table>"
    return f'<div class="scroll">{table}</div>' if scroll else table


# --- sections -------------------------------------------------------------------------------


def _rules_summary(diagnostics: Sequence[Diagnostic], per_link: dict[str, list[Diagnostic]]
                   ) -> str:
    """One row per rule: how many findings, on how many links."""
    by_code: dict[str, list[Diagnostic]] = {}
    for d in diagnostics:
        by_code.setdefault(d.code, []).append(d)
    links_of: dict[str, set[str]] = {}
    for link, items in per_link.items():
        for d in items:
            links_of.setdefault(d.code, set()).add(link)
    rows = []
    for code, items in sorted(by_code.items(), key=lambda kv: (-max(d.severity for d in kv[1]),
                                                              kv[0])):
        first = items[0]
        rows.append(f"<tr><td>{_e(code)}</td><td>{_e(first.name)}</td>"
                    f'<td class="sev-{_e(first.severity)}">{_e(first.severity)}</td>'
                    f"<td class=num>{len(items)}</td>"
                    f"<td class=num>{len(links_of.get(code, ()))}</td></tr>")
    return _table(("code", "rule", "severity", "findings", "links"), rows)


def _findings_section(data: ReportData) -> str:
    result = data.result
    per_link, others = findings_by_link(data.robot, result.diagnostics)
    if not result.diagnostics:
        return '<p class="empty">No findings.</p>'
    groups = list(per_link.items())
    if others:
        groups.append(("(not tied to one link)", others))
    parts = [f"<p>{len(result.diagnostics)} findings on {len(per_link)} links"
             + (f", {len(others)} not tied to one link" if others else "") + ".</p>",
             _rules_summary(result.diagnostics, per_link), '<div class="groups">']
    many = len(groups) > 12
    for name, diagnostics in groups:
        rows = []
        for d in diagnostics:
            fix = f"<pre>{_e(d.fix)}</pre>" if d.fix else ""
            rows.append(f"<tr><td>{_e(d.code)}</td><td class=\"sev-{_e(d.severity)}\">"
                        f"{_e(d.severity)}</td><td>{_e(d.name)}</td>"
                        f"<td>{_e(d.message)}{fix}</td><td class=where>{_e(_location(d))}</td></tr>")
        codes = sorted({d.code for d in diagnostics})
        opened = "" if many else " open"
        parts.append(f'<details{opened} data-link="{_e(name)}"><summary>{_e(name)} '
                     f'<span class="n">{len(diagnostics)}</span> '
                     f'<span class="codes">{_e(", ".join(codes))}</span></summary>'
                     + _table(("code", "severity", "rule", "message", "where"), rows)
                     + "</details>")
    parts.append("</div>")
    return "\n".join(parts)


def _inertia_section(data: ReportData) -> str:
    if data.inertia_rows is None:
        return '<p class="note">The inertia table was not computed.</p>'
    return inertia_rows_html(data.inertia_rows)


def inertia_rows_html(rows: Sequence[InertiaRow]) -> str:
    """The inertia table (`robotdesc.inertia.table.InertiaRow`s) as HTML (also for Jupyter)."""
    if not rows:
        return '<p class="note">No link declares an inertial or has geometry.</p>'
    body = []
    for row in rows:
        suppressed = getattr(row, "suppressed", ())
        marked = (' class="bad"' if row.error is not None and row.error > 0.5
                  and not suppressed else "")
        said = f" (suppressed: {', '.join(suppressed)})" if suppressed else ""
        notes = "; ".join(((f"likely cause: {row.cause}",) if row.cause else ()) + row.notes)
        body.append(
            f"<tr{marked}><td>{_e(row.link)}</td>"
            f"<td>{_e(row.source or '-')}</td><td class=num>{_num(row.declared_mass)}</td>"
            f"<td class=num>{_num(row.volume)}</td><td class=num>{_num(row.density)}</td>"
            f"<td class=vec>{_vec(row.declared_com)}</td>"
            f"<td class=vec>{_vec(row.derived_com)}</td>"
            f"<td class=vec>{_vec(row.declared_moments)}</td>"
            f"<td class=vec>{_vec(row.derived_moments)}</td>"
            f"<td class=num>{'-' if row.error is None else f'{100 * row.error:.1f}%'}"
            f"{_e(said)}</td>"
            f"<td>{_e(notes)}</td></tr>")
    head = ("link", "geometry", "mass kg", "volume m³", "density kg/m³", "COM declared m",
            "COM geometry m", "moments declared kg·m²", "moments geometry kg·m²", "difference",
            "notes")
    return ("<p>Declared inertials against those of each link's geometry at uniform density "
            "and the declared mass; rows over 50% apart are marked.</p>"
            + _table(head, body, scroll=True))


def _collision_rows(data: ReportData) -> list[tuple[str, str, int, str, int]]:
    """(link, visual shapes, visual faces, collision shapes, collision faces) per link."""
    scene = data.scene
    if scene is None:
        return []
    shapes: dict[tuple[str, str], list[str]] = {}
    for instance in scene.instances:
        shapes.setdefault((instance.link, instance.kind), []).append(
            scene.geometries[instance.geometry].label)
    visual, collision = scene.faces_per_link("visual"), scene.faces_per_link("collision")
    rows = []
    for link in scene.links:
        if link in visual or link in collision:
            rows.append((link, ", ".join(shapes.get((link, "visual"), [])), visual.get(link, 0),
                         ", ".join(shapes.get((link, "collision"), [])), collision.get(link, 0)))
    return rows


def _collision_section(data: ReportData) -> str:
    rows = _collision_rows(data)
    parts = []
    if rows:
        body = []
        for link, vshapes, vfaces, cshapes, cfaces in rows:
            ratio = f"{vfaces / cfaces:.3g}" if vfaces and cfaces else "-"
            body.append(f"<tr><td>{_e(link)}</td><td>{_e(vshapes or '-')}</td>"
                        f"<td class=num>{vfaces}</td><td>{_e(cshapes or '-')}</td>"
                        f"<td class=num>{cfaces}</td><td class=num>{ratio}</td></tr>")
        total_v = sum(r[2] for r in rows)
        total_c = sum(r[4] for r in rows)
        parts.append(f"<p>Geometry as described: {total_v} visual and {total_c} collision "
                     "triangles (primitives counted as drawn).</p>")
        parts.append(_table(("link", "visual", "visual triangles", "collision",
                             "collision triangles", "visual : collision"), body, scroll=True))
    if data.collision is not None:
        parts.append(collision_result_html(data.collision))
    return "\n".join(parts) or '<p class="note">No geometry.</p>'


def collision_result_html(result: CollisionResult) -> str:
    """A `CollisionResult` as an HTML heading, totals line and per-link table (also its
    Jupyter display)."""
    body = []
    for outcome in result.outcomes:
        r = outcome.report
        percent = r.percent(r.hausdorff)
        findings = "; ".join(f"{f.severity}: {f.message}" for f in r.findings)
        body.append(f"<tr><td>{_e(r.link)}</td><td>{_e(r.method)}</td><td>{_e(r.status)}</td>"
                    f"<td class=num>{r.faces_before}</td><td class=num>{r.faces_after}</td>"
                    f"<td class=num>{r.hulls or '-'}</td>"
                    f"<td class=num>{_num(r.volume_ratio, 3)}</td>"
                    f"<td class=num>{'-' if percent is None else f'{percent:.2f}%'}</td>"
                    f"<td>{_e(findings)}</td></tr>")
    totals = result.totals()
    ratio = f"{totals['reduction']:.0f}:1" if totals["reduction"] else "-"
    return (f"<h3>Generated collision geometry</h3><p>{totals['written']} of {totals['links']} "
            f"links, triangles {totals['faces_before']} → {totals['faces_after']} ({ratio}), "
            f"{result.seconds:.1f} s.</p>"
            + _table(("link", "method", "status", "triangles before", "after", "hulls",
                      "volume ratio", "Hausdorff (% of diagonal)", "findings"), body,
                     scroll=True))


def _plots_section(data: ReportData) -> str:
    if not plots_available():
        return ('<p class="note">Plots need matplotlib: <code>pip install '
                "'.[report]'</code>.</p>")
    parts = []
    compared = [(r.link, r.declared_moments, r.derived_moments) for r in data.inertia_rows or ()
                if r.declared_moments is not None and r.derived_moments is not None]
    compared.sort(key=lambda row: -_spread(row[1], row[2]))
    compared = _merge_alike(compared)
    svg = moments_plot(compared, total=len(data.inertia_rows or ()))
    if svg:
        parts.append(f'<div class="plot" id="plot-moments">{svg}</div>')
    faces = [(link, v, c) for link, _, v, _, c in _collision_rows(data)]
    total = len(faces)
    faces.sort(key=lambda row: (-row[1], -row[2]))
    svg = faces_plot(_merge_alike(faces), total=total)
    if svg:
        parts.append(f'<div class="plot" id="plot-faces">{svg}</div>')
    return "\n".join(parts) or '<p class="note">Nothing to plot.</p>'


_First = TypeVar("_First")
_Second = TypeVar("_Second")


def _merge_alike(rows: list[tuple[str, _First, _Second]]) -> list[tuple[str, _First, _Second]]:
    """Rows whose values (all but the name) agree to 4 significant digits become one row,
    named after the first with "(+N alike)" (a robot's 100 identical wheels are one line)."""
    def key(row: tuple[str, _First, _Second]) -> tuple[object, ...]:
        return tuple(tuple(float(f"{v:.4g}") for v in value) if isinstance(value, tuple)
                     else value for value in row[1:])

    groups: dict[tuple[object, ...], list[tuple[str, _First, _Second]]] = {}
    for row in rows:
        groups.setdefault(key(row), []).append(row)
    merged: list[tuple[str, _First, _Second]] = []
    for members in groups.values():
        first = members[0]
        name = first[0] + (f" (+{len(members) - 1} alike)" if len(members) > 1 else "")
        merged.append((name, first[1], first[2]))
    return merged


def _spread(declared: Sequence[float], derived: Sequence[float]) -> float:
    """The largest |log10(declared / derived)| over the principal moments (0 if undefined)."""
    values = [abs(math.log10(d / g)) for d, g in zip(declared, derived) if d > 0 and g > 0]
    return max(values, default=0.0)


def _view_section(data: ReportData) -> str:
    if data.scene is None:
        return '<p class="note">The 3D view was not included.</p>'
    from robotdesc.view.encode import scene_document

    per_link, _ = findings_by_link(data.robot, data.result.diagnostics)
    document = scene_document(data.scene, per_link)
    document["show"] = {"visual": True, "collision": False, "inertia": False, "findings": True}
    return view_fragment(document, element_id="robotdesc-view", height="560px")


# --- the page -------------------------------------------------------------------------------


def render_html_report(data: ReportData, title: str | None = None) -> str:
    """The complete, self-contained report page."""

    result, robot = data.result, data.robot
    heading = title or f"{robot.name}: robotdesc report"
    counts = "".join(f'<span class="sev-{_e(level)}">{n} {_e(level)}</span>'
                     for level, n in result.counts.items())
    sections = [("view", "3D view", _view_section(data)),
                ("findings", "Findings by link", _findings_section(data)),
                ("inertia", "Inertia", _inertia_section(data)),
                ("collision", "Collision geometry", _collision_section(data)),
                ("plots", "Plots", _plots_section(data))]
    nav = "".join(f'<a href="#{key}">{_e(name)}</a>' for key, name, _ in sections)
    body = "\n".join(f'<section id="{key}"><h2>{_e(name)}</h2>\n{content}\n</section>'
                     for key, name, content in sections)
    notes = "".join(f'<p class="note">{_e(n)}</p>' for n in data.notes)
    return ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            f"<title>{_e(heading)}</title>\n<meta name=\"generator\" content=\"robotdesc "
            f"{_e(__version__)}\">\n<style>{STYLE}</style>\n</head>\n<body>\n<main>\n"
            f"<h1>{_e(heading)}</h1>\n"
            f'<p class="meta">{_e(os.path.relpath(result.target) if result.target else "")}'
            f" · {len(robot.links)} links, {len(robot.joints)} joints · "
            f"{len(result.rules_run)} of {len(all_rules())} rules ran (as `robotdesc rules` "
            "lists them; opt-in and unselected rules did not)</p>\n"
            f'<p class="counts">{counts}</p>\n<nav>{nav}</nav>\n{notes}\n{body}\n'
            "</main>\n</body>\n</html>\n")
