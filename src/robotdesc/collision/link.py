"""One link's work, run inside a worker process: make the geometry, then measure it.

Pure apart from the native backends: a `LinkTask` in, a `LinkOutcome` out. Engine limits are
checked later by the caller (they are not part of the cache key).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from robotdesc.collision.decimate import decimate, face_budget
from robotdesc.collision.distance import SurfaceIndex
from robotdesc.collision.hull import convex_hull, reduce_hull
from robotdesc.collision.metrics import Fidelity, fidelity, merge_parts, union_volume
from robotdesc.collision.options import CollisionOptions
from robotdesc.collision.result import (
    Finding,
    LinkOutcome,
    LinkReport,
    MeshPart,
    Part,
    PrimitivePart,
)
from robotdesc.collision.tessellate import primitive_mesh
from robotdesc.errors import NoVolumeError
from robotdesc.mesh.records import MassMethod

#: decimate with `adapt`: a budget whose result misses the target is raised by at least
#: this factor, and at most BUDGET_GROWTH_MAX (when far over).
BUDGET_GROWTH = 2.0
BUDGET_GROWTH_MAX = 4.0


@dataclass(frozen=True, eq=False)
class LinkTask:
    """The input of one link's work.

    Attributes:
        link: the link name.
        triangles: (n, 3, 3) soup of the link's source geometry in the link frame (m),
            already validated (finite, non-empty).
        options: the run's parameters.
        key: the cache key of (sources, parameters).
    """

    link: str
    triangles: np.ndarray
    options: CollisionOptions
    key: str = ""


@dataclass(frozen=True)
class _Made:
    method: str
    parts: tuple[Part, ...]
    detail: str = ""
    findings: tuple[Finding, ...] = ()


def run_link(task: LinkTask) -> LinkOutcome:
    """Generate and measure one link's collision geometry (runs in a worker)."""
    from robotdesc.mesh.health import merge_vertices
    from robotdesc.mesh.load import LoadedMesh
    from robotdesc.mesh.summary import summarize

    start = time.perf_counter()
    options = task.options
    vertices, faces = merge_vertices(task.triangles)
    base = LinkReport(task.link, options.method, "failed", faces_before=len(faces),
                      vertices_before=len(vertices))
    summary = summarize(LoadedMesh(task.triangles, task.link, "soup"))
    if summary.properties is None or not summary.properties.volume > 0:
        return _failed(base, start, Finding("no-volume", "error",
                                            "the link's geometry encloses no volume"))
    volume_in = summary.properties.volume
    open_input = summary.method is MassMethod.CONVEX_HULL
    try:
        if options.method == "auto":
            menu = _auto_menu(vertices, faces, options)
        else:
            menu = [MAKERS[options.method](vertices, faces, options)]
    except NoVolumeError as error:
        return _failed(base, start, Finding("no-volume", "error", str(error)))
    except ImportError as error:
        return _failed(base, start, Finding(
            "backend-missing", "error",
            f"{error.name or error}: reinstall robotdesc (its collision dependencies are missing)"))
    outcomes = [_outcome(base, made, measured, volume_in, open_input, task.key)
                for made, measured in menu]
    seconds = time.perf_counter() - start
    outcomes = [replace(o, report=replace(o.report, seconds=seconds)) for o in outcomes]
    if options.method != "auto":
        return outcomes[0]
    return replace(_first_choice(outcomes, options.target_percent),
                   alternatives=tuple(outcomes))


def _outcome(base: LinkReport, made: _Made, measured: Fidelity, volume_in: float,
             open_input: bool, key: str) -> LinkOutcome:
    """One candidate's geometry with its report (errors: no geometry)."""
    surface = [_as_mesh(p) for p in made.parts]
    findings = list(made.findings)
    if open_input:  # VOL cannot be against the input itself
        findings.append(Finding("open-input", "warning", "the input is no closed surface "
                                "(its volume is unknown): VOL is against its convex hull"))
    errors = any(f.severity == "error" for f in findings)
    status = "failed" if errors else "warning" if findings else "ok"
    report = replace(
        base, method=made.method, status=status,
        faces_after=sum(len(p.faces) for p in surface),
        vertices_after=sum(len(p.vertices) for p in surface),
        hulls=sum(1 for p in made.parts if isinstance(p, MeshPart) and p.convex),
        volume_ratio=union_volume(surface) / volume_in,
        forward_mean=measured.forward_mean, forward_max=measured.forward_max,
        backward_mean=measured.backward_mean, backward_max=measured.backward_max,
        diagonal=measured.diagonal, detail=made.detail, findings=tuple(findings))
    if isinstance(made.parts[0], PrimitivePart):
        report = replace(report, faces_after=0, vertices_after=0)
    return LinkOutcome(report, made.parts if not errors else (), key)


def _first_choice(outcomes: list[LinkOutcome], target_percent: float) -> LinkOutcome:
    """Before the robot-wide choice: the cheapest candidate within the link's own target,
    else the most faithful (the choice of `choose.choose_auto` replaces it)."""
    usable = [o for o in outcomes if o.written] or outcomes
    within = [o for o in usable
              if (o.report.percent(o.report.hausdorff) or 0.0) <= target_percent]
    if within:
        return min(within, key=lambda o: o.report.faces_after)
    return min(usable, key=lambda o: o.report.hausdorff or float("inf"))


def _decimate_once(vertices: np.ndarray, faces: np.ndarray, target: int,
                   options: CollisionOptions) -> _Made:
    result = decimate(vertices, faces, target, options.decimator)
    findings = []
    for problem in result.problems:
        severity = "error" if "opened" in problem or "no faces" in problem else "warning"
        code = "target-not-reached" if "stopped" in problem else "broken-result"
        findings.append(Finding(code, severity, f"decimation {problem}"))
    detail = "; ".join((f"budget {target} faces, {result.engine}",) + result.notes)
    return _Made("decimate", (result.part,), detail, tuple(findings))


def _decimate_to_target(vertices: np.ndarray, faces: np.ndarray,
                        options: CollisionOptions) -> tuple[_Made, Fidelity]:
    """Decimate to the `ratio` budget; with `adapt` (and no fixed `faces`), raise the
    budget (`_growth`: 2 to 4 times) and measure again while the Hausdorff distance is over
    the target or the result is broken (it opened the closed input: doubled), up to the
    input's faces or the engine's faces per mesh. A result still over the target gets an
    `over-tolerance` warning naming the option to change and its value."""
    target = face_budget(len(faces), options.ratio, options.faces, options.min_faces)
    adapt = options.adapt and options.faces is None
    cap = max(target, min(len(faces), options.limits.max_mesh_faces))
    budgets = [target]
    index = SurfaceIndex(vertices, faces) if adapt else None  # shared by the measurements
    while True:
        made = _decimate_once(vertices, faces, budgets[-1], options)
        measured = _measure(vertices, faces, made.parts, options, index)
        broken = any(f.severity == "error" for f in made.findings)
        if not adapt or budgets[-1] >= cap or (
                not broken and measured.hausdorff_percent <= options.target_percent):
            break
        # over the target, or broken (an opened surface): a larger budget keeps more of it
        growth = 2.0 if broken else _growth(measured.hausdorff_percent, options.target_percent)
        budgets.append(min(cap, int(budgets[-1] * growth)))
    percent = measured.hausdorff_percent
    decimated = made.parts[0]
    assert isinstance(decimated, MeshPart)  # `_decimate_once` makes one mesh
    kept = len(decimated.faces)
    if len(budgets) > 1:
        steps = " -> ".join(f"{b:,}" for b in budgets)
        made = replace(made, detail=f"budget raised {steps} faces for the "
                                    f"{options.target_percent:g} % target; {made.detail}")
    if percent <= options.target_percent:
        return made, measured
    over = (f"symmetric Hausdorff distance {percent:.2f} % of the diagonal at {kept:,} faces "
            f"is over the target {options.target_percent:g} %")
    advice = f"--target {_round_up(percent)}"
    if adapt and any(f.severity == "error" for f in made.findings):
        message = (f"{over}; the result stayed broken (the error above) with the budget "
                   f"raised to {budgets[-1]:,} faces: use --method coacd, or --method hull")
    elif adapt:
        why = (f"the {options.limits.name} limit of {options.limits.max_mesh_faces:,} faces "
               "per mesh" if len(faces) > options.limits.max_mesh_faces
               else "the input's faces")
        message = (f"{over}, with the budget raised to {why}: accept {advice}, or use "
                   "--method coacd")
    elif options.faces is not None:
        message = (f"{over}: raise --faces (or drop it: the budget then adapts), or "
                   f"accept {advice}")
    else:
        message = f"{over}: drop --no-adapt (the budget then adapts), or accept {advice}"
    return replace(made, findings=made.findings + (
        Finding("over-tolerance", "warning", message),)), measured


def _growth(percent: float, target: float) -> float:
    """How much to raise a face budget whose result is at `percent` for `target`: twice,
    up to four times when far over (the distance falls about as the faces rise)."""
    return min(BUDGET_GROWTH_MAX, max(BUDGET_GROWTH, 1.2 * percent / target))


def _round_up(percent: float) -> str:
    """A target just above `percent`, in a tenth of a percent (as typed on the CLI)."""
    return f"{np.ceil(percent * 10 + 1e-9) / 10:g}"


def _fit_hulls(parts: list[MeshPart], options: CollisionOptions) -> tuple[list[MeshPart], str]:
    """With `adapt`, each hull over the engine's vertex limit reduced to it (and a note)."""
    limit = options.limits.max_hull_vertices
    over = [len(p.vertices) for p in parts if len(p.vertices) > limit]
    if not options.adapt or not over:
        return parts, ""
    fitted = [reduce_hull(p, limit) if len(p.vertices) > limit else p for p in parts]
    return fitted, (f"{len(over)} hull(s) of up to {max(over):,} vertices reduced to the "
                    f"{options.limits.name} limit of {limit}")


def _hull(vertices: np.ndarray, faces: np.ndarray, options: CollisionOptions) -> _Made:
    """One convex hull (reduced to the engine's vertices per hull with `adapt`)."""
    parts, note = _fit_hulls([convex_hull(vertices)], options)
    return _Made("hull", tuple(parts), note)


def _coacd(vertices: np.ndarray, faces: np.ndarray, options: CollisionOptions) -> _Made:
    """CoACD's convex pieces (the input decimated first when over `coacd_input_faces`)."""
    from robotdesc.collision.decompose import coacd_decompose

    notes = [f"threshold {options.threshold:g}, seed {options.seed}"]
    source_v, source_f = vertices, faces
    if options.coacd_input_faces and len(faces) > options.coacd_input_faces:
        simplified = decimate(vertices, faces, options.coacd_input_faces).part
        source_v, source_f = simplified.vertices, simplified.faces
        notes.append(f"input decimated {len(faces):,} -> {len(source_f):,} faces first")
    parts = coacd_decompose(source_v, source_f, threshold=options.threshold,
                            max_hulls=options.max_hulls,
                            hull_vertices=options.hull_vertices,
                            iterations=options.coacd_iterations,
                            depth=options.coacd_depth, nodes=options.coacd_nodes,
                            preprocess_resolution=options.preprocess_resolution,
                            seed=options.seed)
    parts, note = _fit_hulls(parts, options)
    return _Made("coacd", tuple(parts), "; ".join(notes + ([note] if note else [])))


def _primitive(vertices: np.ndarray, faces: np.ndarray, options: CollisionOptions) -> _Made:
    """The best box, cylinder, sphere or capsule by volume overlap."""
    from robotdesc.collision.primitives import fit_primitive

    fitted = fit_primitive(vertices, faces, options.primitives)
    kind = type(fitted.part.geometry).__name__.lower()
    tried = ", ".join(f"{k} {v:.3f}" for k, v in fitted.tried)
    detail = "; ".join((f"{kind}, IoU {fitted.iou:.3f} (tried: {tried})",) + fitted.notes)
    return _Made(f"primitive:{kind}", (fitted.part,), detail)


def _measured(make: Callable[[np.ndarray, np.ndarray, CollisionOptions], _Made]) -> Maker:
    """A geometry maker whose result is then measured against the input."""
    def run(vertices: np.ndarray, faces: np.ndarray,
            options: CollisionOptions) -> tuple[_Made, Fidelity]:
        made = make(vertices, faces, options)
        return made, _measure(vertices, faces, made.parts, options)
    return run


Maker = Callable[[np.ndarray, np.ndarray, CollisionOptions], "tuple[_Made, Fidelity]"]
#: The one table of collision methods (the names, summaries and option fields are in
#: `robotdesc.collision.methods`, import-free): method -> its geometry, measured. `auto` is
#: not here: it makes a menu of these (`_auto_menu`), chosen robot-wide by `choose.py`.
MAKERS: dict[str, Maker] = {
    "decimate": lambda v, f, o: _decimate_to_target(v, f, o),
    "hull": _measured(_hull),
    "coacd": _measured(_coacd),
    "primitive": _measured(_primitive),
}


#: auto: the decimation budgets tried (faces), smallest first, until one meets the target.
AUTO_DECIMATE_BUDGETS = (48, 96, 192, 384, 768, 1536, 3072)
#: auto: the vertices of the reduced convex hulls tried, fewest first.
AUTO_HULL_VERTICES = (12, 24, 48, 96)


def _auto_menu(vertices: np.ndarray, faces: np.ndarray,
               options: CollisionOptions) -> list[tuple[_Made, Fidelity]]:
    """Every candidate of `auto`, measured: the methods of `auto_order` (decimate as a ladder
    of budgets, stopping at the first within the target of the link's own diagonal; coacd
    only when neither a primitive nor the hull meets that target: its time is seconds to
    minutes a link). Which one a link gets is decided robot-wide (`choose.choose_auto`)."""
    menu: list[tuple[_Made, Fidelity]] = []
    notes = []
    for method in options.auto_order:
        if method == "coacd" and any(m.hausdorff_percent <= options.target_percent
                                     for _, m in menu):
            continue
        try:
            if method == "decimate":
                menu.extend(_decimate_ladder(vertices, faces, options))
            elif method == "hull":
                menu.extend(_hull_ladder(vertices, faces, options))
            else:
                menu.append(MAKERS[method](vertices, faces, options))
        except (NoVolumeError, ImportError) as error:
            notes.append(f"{method}: {error}")
    menu = [(made, m) for made, m in menu if not any(f.severity == "error"
                                                      for f in made.findings)]
    if not menu:
        raise NoVolumeError("no method produced geometry: " + "; ".join(notes))
    return menu


def _hull_ladder(vertices: np.ndarray, faces: np.ndarray,
                 options: CollisionOptions) -> list[tuple[_Made, Fidelity]]:
    """The convex hull reduced to AUTO_HULL_VERTICES (fewer triangles: 2V - 4), measured,
    smallest first until one meets the target of the link's own diagonal; else the full hull
    (fitted to the engine's vertices per hull)."""
    full = _hull(vertices, faces, options)
    hull = full.parts[0]
    assert isinstance(hull, MeshPart)  # `_hull` makes one hull
    index = SurfaceIndex(vertices, faces)
    ladder = []
    for count in (c for c in AUTO_HULL_VERTICES if c < len(hull.vertices)):
        reduced = reduce_hull(hull, count)
        made = _Made("hull", (reduced,), f"hull reduced to {len(reduced.vertices)} vertices")
        measured = _measure(vertices, faces, made.parts, options, index)
        ladder.append((made, measured))
        if measured.hausdorff_percent <= options.target_percent:
            return ladder
    return ladder + [(full, _measure(vertices, faces, full.parts, options, index))]


def _decimate_ladder(vertices: np.ndarray, faces: np.ndarray,
                     options: CollisionOptions) -> list[tuple[_Made, Fidelity]]:
    """Decimations at AUTO_DECIMATE_BUDGETS (below the input's faces and the engine's faces
    per mesh), measured, until one meets the target of the link's own diagonal."""
    index = SurfaceIndex(vertices, faces)
    cap = min(len(faces), options.limits.max_mesh_faces)
    budgets = [b for b in AUTO_DECIMATE_BUDGETS if b < cap] or [cap]
    ladder = []
    for budget in budgets:
        made = _decimate_once(vertices, faces, budget, options)
        measured = _measure(vertices, faces, made.parts, options, index)
        ladder.append((made, measured))
        if measured.hausdorff_percent <= options.target_percent and not any(
                f.severity == "error" for f in made.findings):
            break
    return ladder


def _measure(vertices: np.ndarray, faces: np.ndarray, parts: tuple[Part, ...],
             options: CollisionOptions, index: SurfaceIndex | None = None) -> Fidelity:
    surface = merge_parts([_as_mesh(p) for p in parts])
    return fidelity((vertices, faces), surface, options.samples, options.seed, index)


def _as_mesh(part: Part) -> MeshPart:
    if isinstance(part, PrimitivePart):
        return primitive_mesh(part.geometry, part.origin)
    return part


def _failed(base: LinkReport, start: float, finding: Finding) -> LinkOutcome:
    return LinkOutcome(replace(base, status="failed", seconds=time.perf_counter() - start,
                               findings=(finding,)))
