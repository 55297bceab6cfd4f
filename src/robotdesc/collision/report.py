"""The per-link table of a result, as text, plus a total line comparable to Table II of the
Engineer paper (visual polygons before, collision polygons after, their ratio)."""

from __future__ import annotations

from robotdesc.collision.result import CollisionResult, LinkReport

HEADER = ("LINK", "METHOD", "STATUS", "FACES", "HULLS", "VOL", "FWD mm", "BWD mm", "HAUSD",
          "SEC")


def table_rows(result: CollisionResult) -> list[tuple[str, ...]]:
    """One row of cells per link, under `HEADER`: the largest distance from the new geometry
    to the input (FWD) and back (BWD) in mm (the means are in the JSON), Hausdorff as % of the
    bounding diagonal, a status ending in * when the link came from the cache."""
    return [_row(o.report) for o in result.outcomes]


def choice_lines(result: CollisionResult) -> list[str]:
    """Method auto: what each link got and why, identical links (same key) on one line:
    `LINK (+N identical): METHOD, T triangles, Hausdorff D mm: WHY`."""
    if result.options is None or getattr(result.options, "method", "") != "auto":
        return []
    groups: dict[tuple[str, str], list[LinkReport]] = {}
    for outcome in result.outcomes:  # identical and given the same (not left out of contact)
        group = (outcome.key or outcome.report.link, outcome.report.method)
        groups.setdefault(group, []).append(outcome.report)
    lines = ["auto chose:"]
    for reports in groups.values():
        r = reports[0]
        more = f" (+{len(reports) - 1} identical)" if len(reports) > 1 else ""
        distance = "-" if r.hausdorff is None else f"{1000 * r.hausdorff:.2f} mm"
        why = r.detail.split("; ")[0].removeprefix("auto: ")
        lines.append(f"  {r.link}{more}: {r.method}, {r.faces_after:,} triangles, "
                     f"Hausdorff {distance}: {why}")
    return lines


def finding_lines(result: CollisionResult) -> list[str]:
    """Each link's findings, one line each."""
    return [f"{outcome.report.link}: {finding.severity}: [{finding.code}] {finding.message}"
            for outcome in result.outcomes for finding in outcome.report.findings]


def total_line(result: CollisionResult) -> str:
    """The totals, comparable to Table II of the Engineer paper."""
    totals = result.totals()
    ratio = f"{totals['reduction']:.0f}:1" if totals["reduction"] else "-"
    primitives = f"{totals['primitives']} primitives, " if totals["primitives"] else ""
    return (f"total: {totals['written']}/{totals['links']} links, "
            f"faces {totals['faces_before']}->{totals['faces_after']} ({ratio}), {primitives}"
            f"{totals['hulls']} hulls, {totals['cached']} cached (*), "
            f"{result.seconds:.2f} s with {result.jobs} job(s)")


def _row(r: LinkReport) -> tuple[str, ...]:
    def mm(value: float | None) -> str:
        return "-" if value is None else f"{1000 * value:.2f}"

    percent = r.percent(r.hausdorff)
    return (r.link, r.method, r.status + ("*" if r.cached else ""),
            f"{r.faces_before}->{r.faces_after}", str(r.hulls or "-"),
            "-" if r.volume_ratio is None else f"{r.volume_ratio:.2f}",
            mm(r.forward_max), mm(r.backward_max),
            "-" if percent is None else f"{percent:.2f}%", f"{r.seconds:.2f}")
