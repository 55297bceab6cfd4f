"""Defaults that pass their own checks: decimate adapts its budget to the target, hulls fit
the engine's vertex limit, and every finding says which option to change."""

from __future__ import annotations

import numpy as np
import pytest

import robotdesc
from collision.conftest import LINK1, real_mesh, write_urdf
from robotdesc.collision import generate as generate_module
from robotdesc.collision.decimate import is_closed
from robotdesc.collision.hull import contains, convex_hull, reduce_hull
from robotdesc.collision.limits import EngineLimits
from robotdesc.collision.link import LinkTask, run_link
from robotdesc.collision.options import CollisionOptions
from robotdesc.errors import CollisionOptionError
from robotdesc.mesh.health import merge_vertices
from robotdesc.mesh.load import load_mesh


@pytest.fixture(scope="module")
def link1():
    """Panda link 1 (12,516 faces): 1.05 % of its diagonal at the 2 % budget."""
    return load_mesh(real_mesh(LINK1)).triangles


def _codes(report):
    return [f.code for f in report.findings]


def test_decimate_raises_its_budget_until_the_target_is_met(link1):
    report = run_link(LinkTask("link1", link1, CollisionOptions("decimate"))).report
    assert report.status == "ok", report.findings
    assert report.percent(report.hausdorff) <= 1.0
    assert "budget raised 251 -> 502 faces for the 1 % target" in report.detail
    assert report.faces_after <= 502 * 1.05 + 4


def test_without_adapting_the_finding_names_the_option_and_value(link1):
    fixed = run_link(LinkTask("link1", link1, CollisionOptions("decimate", adapt=False))).report
    assert _codes(fixed) == ["over-tolerance"]
    message = fixed.findings[0].message
    assert "drop --no-adapt" in message and "--target 1.1" in message
    budget = run_link(LinkTask("link1", link1, CollisionOptions("decimate", faces=250))).report
    assert "raise --faces" in budget.findings[0].message


def test_the_budget_stops_at_the_engines_face_limit(link1):
    limits = EngineLimits("tiny", max_mesh_faces=300)
    options = CollisionOptions("decimate", limits=limits, target_percent=0.3)
    report = run_link(LinkTask("link1", link1, options)).report
    [finding] = report.findings
    assert finding.code == "over-tolerance"
    assert "limit of 300 faces per mesh" in finding.message
    assert "--target" in finding.message and "--method coacd" in finding.message
    assert report.faces_after <= 300 * 1.05 + 4


def test_reduce_hull_fits_the_limit_inside_the_hull(link1):
    vertices, _ = merge_vertices(link1)
    hull = convex_hull(vertices)
    assert len(hull.vertices) > 40
    small = reduce_hull(hull, 40)
    assert small.convex and len(small.vertices) <= 40
    assert is_closed(small.vertices, small.faces)
    diagonal = np.linalg.norm(vertices.max(0) - vertices.min(0))
    assert contains(hull, small.vertices, tolerance=1e-9 * diagonal).all()
    assert reduce_hull(small, 40) is small


def test_the_hull_method_respects_the_vertex_limit_by_default(link1):
    limits = EngineLimits("tiny", max_hull_vertices=40)
    report = run_link(LinkTask("link1", link1, CollisionOptions("hull", limits=limits))).report
    assert report.status == "ok" and report.vertices_after <= 40
    assert "reduced to the tiny limit of 40" in report.detail
    kept = run_link(LinkTask("link1", link1,
                             CollisionOptions("hull", limits=limits, adapt=False))).report
    assert kept.vertices_after > 40


@pytest.mark.slow
def test_hull_meets_physx_by_default_end_to_end(package):
    urdf = write_urdf(package, {"hip": "hip.stl", "leg": "leg.stl"})
    result = robotdesc.generate_collision(robotdesc.load(str(urdf)), "hull", jobs=1,
                                          use_cache=False)
    for outcome in result.outcomes:
        assert "over-limit" not in _codes(outcome.report)
        assert max(len(p.vertices) for p in outcome.parts) <= 255


def test_limits_and_adapt_are_in_the_key_of_the_methods_that_read_them():
    tight = EngineLimits("tight", max_hull_vertices=32, max_mesh_faces=100)
    for method in ("decimate", "hull", "coacd"):
        base = CollisionOptions(method)
        assert base.key_fields() != CollisionOptions(method, adapt=False).key_fields()
        assert base.key_fields() != CollisionOptions(method, limits=tight).key_fields()
    assert CollisionOptions("primitive").key_fields() == \
        CollisionOptions("primitive", limits=tight, adapt=False).key_fields()
    with pytest.raises(CollisionOptionError, match="coacd input faces"):
        CollisionOptions(coacd_input_faces=2).validated()


def test_a_timeout_names_the_link_and_mesh_timeout(package, monkeypatch):
    from collision import faults

    urdf = write_urdf(package, {"good": "hip.stl", "slow": "leg.stl"})
    monkeypatch.setattr(generate_module, "LINK_RUNNER", faults.stall_on_slow_link)
    result = robotdesc.generate_collision(robotdesc.load(str(urdf)), "hull", jobs=2,
                                          use_cache=False, mesh_timeout_s=3)
    by_link = {o.report.link: o.report for o in result.outcomes}
    assert by_link["good"].status == "ok"
    [finding] = by_link["slow"].findings
    assert finding.code == "worker-timeout"
    assert "link slow" in finding.message and "--mesh-timeout 6" in finding.message
