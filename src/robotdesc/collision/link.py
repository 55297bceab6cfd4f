"""One link's work, run inside a worker process: make the geometry, then measure it.

Pure apart from the native backends: a `LinkTask` in, a `LinkOutcome` out. Engine limits are
checked later by the caller (they are not part of the cache key).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from robotdesc.collision.decimate import decimate, face_budget
from robotdesc.collision.hull import NoVolumeError, convex_hull
from robotdesc.collision.metrics import Fidelity, fidelity, merge_parts, union_volume
from robotdesc.collision.options import CollisionOptions
from robotdesc.collision.result import Finding, LinkOutcome, LinkReport, MeshPart, Part, \
    PrimitivePart
from robotdesc.collision.tessellate import primitive_mesh


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
    try:
        if options.method == "auto":
            made, measured = _auto(vertices, faces, options)
        else:
            made = _make(options.method, vertices, faces, options)
            measured = _measure(vertices, faces, made.parts, options)
    except NoVolumeError as error:
        return _failed(base, start, Finding("no-volume", "error", str(error)))
    except ImportError as error:
        return _failed(base, start, Finding(
            "backend-missing", "error",
            f"{error.name or error}: reinstall robotdesc (its collision dependencies are missing)"))
    surface = [_as_mesh(p) for p in made.parts]
    findings = list(made.findings)
    if options.method == "decimate" and measured.hausdorff_percent > options.target_percent:
        findings.append(Finding(
            "over-tolerance", "warning",
            f"symmetric Hausdorff distance {measured.hausdorff_percent:.2f} % of the "
            f"diagonal is over the target {options.target_percent:g} %"))
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
        diagonal=measured.diagonal, seconds=time.perf_counter() - start,
        detail=made.detail, findings=tuple(findings))
    if isinstance(made.parts[0], PrimitivePart):
        report = replace(report, faces_after=0, vertices_after=0)
    return LinkOutcome(report, made.parts if not errors else (), task.key)


def _make(method: str, vertices: np.ndarray, faces: np.ndarray,
          options: CollisionOptions) -> _Made:
    if method == "hull":
        return _Made("hull", (convex_hull(vertices),))
    if method == "decimate":
        target = face_budget(len(faces), options.ratio, options.faces, options.min_faces)
        result = decimate(vertices, faces, target, options.decimator)
        findings = []
        for problem in result.problems:
            severity = "error" if "opened" in problem or "no faces" in problem else "warning"
            code = "target-not-reached" if "stopped" in problem else "broken-result"
            findings.append(Finding(code, severity, f"decimation {problem}"))
        detail = "; ".join((f"budget {target} faces, {result.engine}",) + result.notes)
        return _Made("decimate", (result.part,), detail, tuple(findings))
    if method == "coacd":
        from robotdesc.collision.decompose import coacd_decompose

        parts = coacd_decompose(vertices, faces, threshold=options.threshold,
                                max_hulls=options.max_hulls,
                                hull_vertices=options.hull_vertices,
                                iterations=options.coacd_iterations,
                                preprocess_resolution=options.preprocess_resolution,
                                seed=options.seed)
        return _Made("coacd", tuple(parts), f"threshold {options.threshold:g}, seed "
                                            f"{options.seed}")
    if method == "primitive":
        from robotdesc.collision.primitives import fit_primitive

        fitted = fit_primitive(vertices, faces, options.primitives)
        kind = type(fitted.part.geometry).__name__.lower()
        tried = ", ".join(f"{k} {v:.3f}" for k, v in fitted.tried)
        detail = "; ".join((f"{kind}, IoU {fitted.iou:.3f} (tried: {tried})",) + fitted.notes)
        return _Made(f"primitive:{kind}", (fitted.part,), detail)
    raise ValueError(f"unknown method {method!r}")


def _auto(vertices: np.ndarray, faces: np.ndarray,
          options: CollisionOptions) -> tuple[_Made, Fidelity]:
    """The first method in `auto_order` meeting the target; else the most faithful."""
    tried: list[tuple[_Made, Fidelity]] = []
    notes = []
    for method in options.auto_order:
        try:
            made = _make(method, vertices, faces, options)
        except (NoVolumeError, ImportError) as error:
            notes.append(f"{method}: {error}")
            continue
        if any(f.severity == "error" for f in made.findings):
            notes.append(f"{method}: {made.findings[0].message}")
            continue
        measured = _measure(vertices, faces, made.parts, options)
        notes.append(f"{method} {measured.hausdorff_percent:.2f} %")
        if measured.hausdorff_percent <= options.target_percent:
            return replace(made, detail=f"auto ({', '.join(notes)}): {made.detail}"), measured
        tried.append((made, measured))
    if not tried:
        raise NoVolumeError("no method produced geometry: " + "; ".join(notes))
    made, measured = min(tried, key=lambda pair: pair[1].hausdorff_percent)
    finding = Finding("target-not-met", "warning",
                      f"no method met the target of {options.target_percent:g} % "
                      f"({', '.join(notes)}); kept the most faithful, {made.method}")
    return replace(made, detail=f"auto: {made.detail}",
                   findings=made.findings + (finding,)), measured


def _measure(vertices: np.ndarray, faces: np.ndarray, parts: tuple[Part, ...],
             options: CollisionOptions) -> Fidelity:
    surface = merge_parts([_as_mesh(p) for p in parts])
    return fidelity((vertices, faces), surface, options.samples, options.seed)


def _as_mesh(part: Part) -> MeshPart:
    if isinstance(part, PrimitivePart):
        return primitive_mesh(part.geometry, part.origin)
    return part


def _failed(base: LinkReport, start: float, finding: Finding) -> LinkOutcome:
    return LinkOutcome(replace(base, status="failed", seconds=time.perf_counter() - start,
                               findings=(finding,)))
