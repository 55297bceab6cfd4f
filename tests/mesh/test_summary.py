"""Summaries and their stated fallbacks: never a negative or NaN mass."""

from __future__ import annotations

import math

import numpy as np
import pytest

from robotdesc.mesh.analyze import analyze_mesh_file
from robotdesc.mesh.load import LoadedMesh
from robotdesc.mesh.summary import MassMethod, summarize

from .builders import box_triangles, write_binary_stl


def _summary(soup):
    return summarize(LoadedMesh(np.asarray(soup, dtype=float), "test.stl", "stl"))


def _assert_sane(summary):
    props = summary.properties
    assert props is not None and props.mass > 0 and props.volume > 0
    assert not any(math.isnan(v) for row in props.inertia for v in row)
    assert min(props.principal_moments()) > 0


def test_closed_box_is_exact():
    summary = _summary(box_triangles(center=(1.0, 0.0, 0.0)))
    assert summary.method is MassMethod.EXACT and summary.notes == ()
    assert summary.properties.volume == pytest.approx(6.0)
    assert summary.bounds == ((0.5, -1.0, -1.5), (1.5, 1.0, 1.5))
    assert summary.extent == (1.0, 2.0, 3.0)


def test_inverted_mesh_is_flipped_and_said_so():
    summary = _summary(box_triangles()[:, ::-1])
    assert summary.method is MassMethod.FLIPPED
    assert summary.signed_volume == pytest.approx(-6.0)
    assert summary.properties.volume == pytest.approx(6.0)
    assert "inverted" in summary.notes[0]
    _assert_sane(summary)


def test_open_mesh_gets_its_holes_capped():
    summary = _summary(box_triangles()[2:])
    assert summary.method is MassMethod.HOLES_CAPPED
    assert summary.properties.volume == pytest.approx(6.0)
    assert "open (4 boundary edges in 1 loops)" in summary.notes[0]
    _assert_sane(summary)


def test_open_and_inverted_is_capped_and_flipped():
    summary = _summary(box_triangles()[2:, ::-1])
    assert summary.method is MassMethod.HOLES_CAPPED
    assert summary.properties.volume == pytest.approx(6.0)
    assert any("inverted" in note for note in summary.notes)


def test_misoriented_mesh_falls_back_to_the_convex_hull():
    soup = np.concatenate([box_triangles(), box_triangles((0.5, 0.5, 0.5), center=(3, 0, 0))])
    soup[1] = soup[1][::-1]
    summary = _summary(soup[1:])  # open and misoriented: not safe to cap
    assert summary.method is MassMethod.CONVEX_HULL
    assert "convex hull" in summary.notes[0]
    assert summary.properties.volume > 6.0  # the hull spans both boxes
    _assert_sane(summary)


def test_flat_surface_has_no_mass_properties():
    square = np.array([[[0, 0, 0], [1, 0, 0], [1, 1, 0]], [[0, 0, 0], [1, 1, 0], [0, 1, 0]]],
                      dtype=float)
    summary = _summary(square)
    assert summary.method is MassMethod.NONE and summary.properties is None
    assert "span no volume" in summary.notes[0]


def test_analyze_file_with_urdf_scale(tmp_path):
    path = write_binary_stl(tmp_path / "mm.stl", box_triangles((10.0, 20.0, 30.0)))
    summary = analyze_mesh_file(path, scale=(0.01, 0.01, 0.01))
    assert summary.properties.volume == pytest.approx(6e-3, rel=1e-6)
