"""The per-link table of a result, as text, plus a total line comparable to Table II of the
Engineer paper (visual polygons before, collision polygons after, their ratio)."""

from __future__ import annotations

from robotdesc.collision.result import CollisionResult, LinkReport

HEADER = ("LINK", "METHOD", "STATUS", "FACES", "HULLS", "VOL", "FWD MEAN/MAX", "BWD MEAN/MAX",
          "HAUSD", "TIME")


def render_table(result: CollisionResult) -> str:
    """A fixed-width table; distances in mm, Hausdorff as % of the bounding diagonal."""
    rows = [HEADER] + [_row(o.report) for o in result.outcomes]
    widths = [max(len(r[i]) for r in rows) for i in range(len(HEADER))]
    lines = ["  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip() for r in rows]
    for outcome in result.outcomes:
        for finding in outcome.report.findings:
            lines.append(f"{outcome.report.link}: {finding.severity}: [{finding.code}] "
                         f"{finding.message}")
    totals = result.totals()
    ratio = f"{totals['reduction']:.0f}:1" if totals["reduction"] else "-"
    lines.append(f"total: {totals['written']}/{totals['links']} links, faces "
                 f"{totals['faces_before']} -> {totals['faces_after']} ({ratio}), "
                 f"{totals['hulls']} hulls, {totals['cached']} cached, "
                 f"{result.seconds:.2f} s wall with {result.jobs} job(s)")
    return "\n".join(lines) + "\n"


def _row(r: LinkReport) -> tuple[str, ...]:
    def mm(value: float | None) -> str:
        return "-" if value is None else f"{1000 * value:.2f}"

    percent = r.percent(r.hausdorff)
    return (r.link, r.method, r.status + (" (cached)" if r.cached else ""),
            f"{r.faces_before}->{r.faces_after}", str(r.hulls or "-"),
            "-" if r.volume_ratio is None else f"{r.volume_ratio:.2f}",
            f"{mm(r.forward_mean)}/{mm(r.forward_max)}mm",
            f"{mm(r.backward_mean)}/{mm(r.backward_max)}mm",
            "-" if percent is None else f"{percent:.2f}%", f"{r.seconds:.2f}s")
