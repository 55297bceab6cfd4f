"""The robot-wide choice of method `auto`: per link, geometry cheap to simulate and close
enough, under a triangle budget for the whole robot.

Each link's worker made and measured a menu of candidates (`LinkOutcome.alternatives`: the
best primitive, the convex hull, decimations at rising budgets, CoACD pieces when nothing
convex fits). Here, per group of identical links (same sources and parameters: the
Engineer's 212 track wheels are one group, decided once):

1. the tolerance is in the robot's own scale: `target_percent` of the largest link's
   bounding-box diagonal (m), the same for every link;
2. each group takes its cheapest candidate within the tolerance (triangles the engine
   collides; a primitive costs none and wins a tie), else its most faithful one (a
   `target-not-met` warning naming the `--target` that would pass);
3. while the robot's triangles (summed over every link) exceed `budget_triangles`, the group
   whose cheaper candidate adds the least distance per triangle saved takes it (the reason
   says so: an `info`, the user's budget asked for it); a budget still exceeded when no
   cheaper candidate is left is an `over-budget` warning naming the `--budget` that would pass.

Links named in `no_contact` get no collision at all (the user asked: e.g. a track's belt
that touches the ground only through its wheels), said in their detail.
"""

from __future__ import annotations

import fnmatch
from collections.abc import Sequence
from dataclasses import dataclass, replace

from robotdesc.collision.options import CollisionOptions
from robotdesc.collision.result import Finding, LinkOutcome, LinkReport
from robotdesc.errors import CollisionOptionError

#: The method reported for a link left out of contact on request.
NO_CONTACT = "none"


@dataclass(frozen=True)
class _Group:
    """Identical links (indices into the outcomes) and their candidates."""

    indices: tuple[int, ...]
    candidates: tuple[LinkOutcome, ...]


def _distance(outcome: LinkOutcome) -> float:
    return outcome.report.hausdorff if outcome.report.hausdorff is not None else float("inf")


#: Equal triangles: a primitive first, then a convex hull (every engine collides it natively),
#: then convex pieces, then a mesh.
_RANK = {"primitive": 0, "hull": 1, "coacd": 2, "decimate": 3}


def _cost(outcome: LinkOutcome) -> tuple[int, int, float]:
    """(triangles, kind, distance): what a candidate costs an engine, cheapest first."""
    kind = _RANK.get(outcome.report.method.split(":")[0], 4)
    return outcome.report.faces_after, kind, _distance(outcome)


def robot_scale(outcomes: Sequence[LinkOutcome]) -> float:
    """The robot's size for the tolerance (m): its largest link's bounding-box diagonal."""
    return max((a.report.diagonal for o in outcomes for a in (o, *o.alternatives)),
               default=0.0)


def left_out(names: Sequence[str], patterns: Sequence[str]) -> set[str]:
    """The link names matching `patterns` (shell patterns, e.g. `*_track_link`).

    Raises:
        CollisionOptionError: a pattern matches no link (a typo must not pass silently).
    """
    chosen: set[str] = set()
    for pattern in patterns:
        matched = {n for n in names if fnmatch.fnmatchcase(n, pattern)}
        if not matched:
            raise CollisionOptionError("no_contact", pattern,
                                       f"--no-contact {pattern!r} matches no link with geometry")
        chosen |= matched
    return chosen


def no_contact_outcome(outcome: LinkOutcome) -> LinkOutcome:
    """`outcome`'s link with no collision geometry, as the user asked."""
    report = LinkReport(outcome.report.link, NO_CONTACT, "ok",
                        faces_before=outcome.report.faces_before,
                        vertices_before=outcome.report.vertices_before,
                        cached=outcome.report.cached,
                        detail="left out of contact on request (--no-contact): no "
                               "<collision>")
    return LinkOutcome(report, (), outcome.key)


def choose_auto(outcomes: Sequence[LinkOutcome],
                options: CollisionOptions) -> tuple[LinkOutcome, ...]:
    """Each link's candidate under the robot-wide tolerance and budget (see the module)."""
    result = list(outcomes)
    groups: dict[str, list[int]] = {}
    for index, outcome in enumerate(outcomes):
        usable = [a for a in outcome.alternatives if a.written]
        if usable:
            groups.setdefault(outcome.key or f"#{index}", []).append(index)
    if not groups:
        return tuple(result)
    scale = robot_scale(outcomes)
    tolerance = options.target_percent / 100.0 * scale
    tol_text = (f"{1000 * tolerance:.2f} mm ({options.target_percent:g} % of the robot's "
                f"largest link, {1000 * scale:.0f} mm)")
    picks: dict[str, LinkOutcome] = {}
    whys: dict[str, str] = {}
    members: dict[str, _Group] = {}
    for key, indices in groups.items():
        candidates = tuple(a for a in outcomes[indices[0]].alternatives if a.written)
        members[key] = _Group(tuple(indices), candidates)
        within = [a for a in candidates if _distance(a) <= tolerance]
        if within:
            picks[key] = min(within, key=_cost)
            whys[key] = f"cheapest of {len(candidates)} candidates within {tol_text}"
        else:
            picks[key] = min(candidates, key=_distance)
            whys[key] = f"no candidate within {tol_text}: the most faithful"

    def total() -> int:
        return sum(picks[k].report.faces_after * len(g.indices) for k, g in members.items())

    budget = options.budget_triangles
    traded: set[str] = set()
    while budget and total() > budget:
        best: tuple[float, str, LinkOutcome] | None = None
        for key, group in members.items():
            current = picks[key]
            for candidate in group.candidates:
                saved = (current.report.faces_after - candidate.report.faces_after) \
                    * len(group.indices)
                if saved <= 0:
                    continue
                score = max(_distance(candidate) - _distance(current), 0.0) / saved
                if best is None or score < best[0]:
                    best = (score, key, candidate)
        if best is None:
            break
        _, key, candidate = best
        before = picks[key]
        picks[key] = candidate
        if key not in traded:
            whys[key] = (f"the robot's budget of {budget:,} triangles: "
                         f"{_label(before)} traded for {_label(candidate)}")
            traded.add(key)
        else:
            whys[key] = whys[key].rsplit(" traded for ", 1)[0] + f" traded for {_label(candidate)}"
    over = total() > budget if budget else False
    biggest = max(members, key=lambda k: picks[k].report.faces_after * len(members[k].indices))
    for key, group in members.items():
        pick = picks[key]
        findings = list(pick.report.findings)
        if _distance(pick) > tolerance and key not in traded:
            needed = 100.0 * _distance(pick) / scale if scale > 0 else 0.0
            findings.append(Finding(
                "target-not-met", "warning",
                f"no candidate within {tol_text}; kept the most faithful, {pick.report.method} "
                f"at {1000 * _distance(pick):.2f} mm: accept --target {_round_up(needed)}, "
                "or leave the link out of contact with --no-contact if it touches nothing"))
        elif key in traded:
            findings.append(Finding("budget", "info", whys[key]))
        if over and key == biggest:
            findings.append(Finding(
                "over-budget", "warning",
                f"the robot's collision has {total():,} triangles, over the budget of "
                f"{budget:,} with every link at its cheapest candidate: accept --budget "
                f"{total():,}, or --no-contact for links that touch nothing"))
        status = "warning" if any(f.severity in ("warning", "error") for f in findings) \
            else "ok"
        for index in group.indices:
            original = outcomes[index].report
            report = replace(pick.report, link=original.link, cached=original.cached,
                             seconds=original.seconds, status=status,
                             detail=f"auto: {whys[key]}; {pick.report.detail}",
                             findings=tuple(findings))
            result[index] = replace(pick, report=report, key=outcomes[index].key,
                                    alternatives=outcomes[index].alternatives)
    return tuple(result)


def _label(outcome: LinkOutcome) -> str:
    r = outcome.report
    distance = f"{1000 * r.hausdorff:.2f} mm" if r.hausdorff is not None else "-"
    return f"{r.method} ({r.faces_after:,} triangles, {distance})"


def _round_up(percent: float) -> str:
    return f"{int(percent * 10 + 0.999999) / 10:g}"
