"""Each method on real example-robot-data meshes, with fidelity bounds asserted."""

from __future__ import annotations

import numpy as np
import pytest

from collision.conftest import (
    FOREARM,
    HIP,
    LINK1,
    SO101_HOLDER,
    UPPERARM,
    Z1_LINK03,
    Z1_LINK05,
    box_soup,
    real_mesh,
)
from robotdesc.collision import link as link_module
from robotdesc.collision.decimate import BUDGET_SLACK, decimate, face_budget, is_closed
from robotdesc.collision.hull import contains, convex_hull
from robotdesc.collision.link import LinkTask, run_link
from robotdesc.collision.metrics import Fidelity, fidelity
from robotdesc.collision.options import CollisionOptions
from robotdesc.collision.result import Finding
from robotdesc.collision.tessellate import primitive_mesh
from robotdesc.errors import CollisionOptionError, NoVolumeError
from robotdesc.mesh.health import merge_vertices
from robotdesc.mesh.load import load_mesh
from robotdesc.model.elements import Cylinder, Pose


def _mesh(relative):
    return merge_vertices(load_mesh(real_mesh(relative)).triangles)


# The bound: at 2 % of the faces, a dense closed mesh keeps its symmetric Hausdorff
# distance under 1 % of its diagonal (measured with meshoptimizer 0.2.30a0: UR5 upper arm
# 0.73 %, z1 link 3 0.33 %, SO-101 motor holder 0.22 %). Coarser meshes need more faces: the
# 12.5k-face Panda link is at 1.05 % with 2 % and under 1 % with 20 %.
@pytest.mark.parametrize("relative, ratio, bound", [
    (UPPERARM, 0.02, 1.0), (Z1_LINK03, 0.02, 1.0), (SO101_HOLDER, 0.02, 1.0),
    (FOREARM, 0.02, 1.2), (LINK1, 0.02, 1.5), (LINK1, 0.2, 1.0)])
def test_decimation_stays_closed_and_within_bounds(relative, ratio, bound):
    vertices, faces = _mesh(relative)
    assert is_closed(vertices, faces)
    target = face_budget(len(faces), ratio, None, 64)
    result = decimate(vertices, faces, target)
    part = result.part
    assert result.engine == "meshoptimizer" and not result.problems
    assert len(part.faces) <= target * (1 + BUDGET_SLACK) + 4
    assert is_closed(part.vertices, part.faces)
    measured = fidelity((vertices, faces), (part.vertices, part.faces))
    assert measured.hausdorff_percent < bound


def test_a_stalled_engine_falls_back_and_says_so():
    vertices, faces = _mesh(UPPERARM)
    target = face_budget(len(faces), 0.02, None, 64)
    result = decimate(vertices, faces, target, engine="fast-simplification")
    assert result.engine == "meshoptimizer" and not result.problems
    assert any("fast-simplification stopped at" in note for note in result.notes)
    assert len(result.part.faces) <= target * (1 + BUDGET_SLACK) + 4


def test_the_default_engine_is_far_more_faithful_than_fast_simplification():
    """Why meshoptimizer is the default: on this z1 link, fast-simplification reaches the
    budget (so no fallback runs) with a 21 % Hausdorff distance."""
    vertices, faces = _mesh(Z1_LINK05)
    target = face_budget(len(faces), 0.02, None, 64)
    results = {engine: decimate(vertices, faces, target, engine=engine)
               for engine in ("meshoptimizer", "fast-simplification")}
    percent = {engine: fidelity((vertices, faces), (r.part.vertices, r.part.faces))
               .hausdorff_percent for engine, r in results.items()}
    assert results["fast-simplification"].engine == "fast-simplification"
    assert percent["meshoptimizer"] < 1.0 < 10.0 < percent["fast-simplification"]


def test_unknown_engine_is_refused():
    vertices, faces = _mesh(HIP)
    with pytest.raises(CollisionOptionError, match="unknown decimation engine"):
        decimate(vertices, faces, 100, engine="blender")


def test_hull_covers_the_input():
    vertices, faces = _mesh(LINK1)
    hull = convex_hull(vertices)
    assert hull.convex and is_closed(hull.vertices, hull.faces)
    diagonal = np.linalg.norm(vertices.max(0) - vertices.min(0))
    assert contains(hull, vertices, tolerance=1e-9 * diagonal).all()


def test_hull_of_flat_points_is_no_volume():
    flat = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], dtype=float)
    with pytest.raises(NoVolumeError):
        convex_hull(flat)


def test_primitive_recovers_a_tilted_cylinder():
    origin = Pose((0.1, -0.2, 0.3), (0.4, 0.2, -0.7))
    truth = primitive_mesh(Cylinder(0.05, 0.3), origin)
    outcome = run_link(LinkTask("tube", truth.vertices[truth.faces],
                                CollisionOptions(method="primitive")))
    report = outcome.report
    assert report.method == "primitive:cylinder", report.detail
    assert report.percent(report.hausdorff) < 1.0
    assert report.volume_ratio == pytest.approx(1.0, abs=0.02)


def test_primitive_on_a_real_mesh_reports_overlap():
    vertices, faces = _mesh(HIP)
    outcome = run_link(LinkTask("hip", vertices[faces], CollisionOptions(method="primitive")))
    assert outcome.report.status == "ok"
    assert "IoU" in outcome.report.detail
    assert outcome.report.volume_ratio > 0.5


@pytest.mark.slow
def test_coacd_is_deterministic_and_within_its_limits():
    vertices, faces = _mesh(HIP)
    options = CollisionOptions(method="coacd", max_hulls=8, hull_vertices=32)
    first = run_link(LinkTask("hip", vertices[faces], options))
    second = run_link(LinkTask("hip", vertices[faces], options))
    assert first.report.status == "ok", first.report.findings
    assert 1 <= first.report.hulls <= 8
    assert all(len(p.vertices) <= 32 for p in first.parts)
    assert all(np.array_equal(a.vertices, b.vertices) for a, b in zip(first.parts, second.parts))
    # the union of hulls covers the input up to CoACD's own tolerance
    assert first.report.percent(first.report.forward_max) < 10
    assert 0.9 < first.report.volume_ratio < 1.5


def test_a_broken_decimation_raises_its_budget_and_says_so(monkeypatch):
    """When decimation opens a closed mesh, a larger budget is tried (held-out: an Allegro
    link closed again at 512 faces of 1,400); one broken up to the cap says so."""
    real_once = link_module._decimate_once

    def broken(vertices, faces, target, options):
        made = real_once(vertices, faces, target, options)
        return link_module.replace(made, findings=(
            Finding("broken-result", "error", "decimation opened the closed input"),))

    monkeypatch.setattr(link_module, "_decimate_once", broken)
    monkeypatch.setattr(link_module, "_measure", lambda *a, **k: fidelity_at(3.0))
    vertices, faces = _mesh(UPPERARM)
    made, _ = link_module._decimate_to_target(vertices, faces, CollisionOptions())
    [warning] = [f for f in made.findings if f.code == "over-tolerance"]
    cap = min(len(faces), CollisionOptions().limits.max_mesh_faces)
    assert f"stayed broken (the error above) with the budget raised to {cap:,}" \
        in warning.message
    assert "budget raised" in made.detail


def fidelity_at(percent: float) -> Fidelity:
    return Fidelity(0.0, percent / 100, 0.0, percent / 100, 1.0)


def test_an_input_that_is_no_closed_surface_says_what_vol_is_against():
    """UR's upper arm mesh has non-manifold edges: its volume is unknown, VOL is against its
    convex hull, and the report says so instead of showing 0.54 as if volume were lost."""
    soup = box_soup()
    soup = np.concatenate([soup, soup[:1], soup[:1]])  # one face three times: non-manifold
    outcome = run_link(LinkTask("arm", soup, CollisionOptions(method="hull")))
    codes = [f.code for f in outcome.report.findings]
    assert "open-input" in codes and outcome.report.status == "warning"
    closed = run_link(LinkTask("arm", box_soup(), CollisionOptions(method="hull")))
    assert "open-input" not in [f.code for f in closed.report.findings]
