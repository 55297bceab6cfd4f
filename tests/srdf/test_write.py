import json

import pytest
from lxml import etree

pytest.importorskip("pinocchio")

from kinematics.robots import ARM, robot  # noqa: E402

from robotdesc.srdf import compute_matrix, render_report, render_srdf  # noqa: E402


def test_srdf_is_valid_xml_with_one_element_per_disabled_pair() -> None:
    matrix = compute_matrix(robot(ARM), lambda mesh: None, samples=100, seed=2, workers=1)
    text = render_srdf(matrix)
    root = etree.fromstring(text.encode())
    found = [(e.get("link1"), e.get("link2"), e.get("reason")) for e in root]
    assert root.get("name") == "arm" and "100 random configurations" in text and "seed 2" in text
    assert found == [(p.link1, p.link2, p.reason.value) for p in matrix.disabled()]
    assert text == render_srdf(compute_matrix(robot(ARM), lambda mesh: None, samples=100,
                                              seed=2, workers=1))


def test_report_lists_fractions_samples_and_seed() -> None:
    matrix = compute_matrix(robot(ARM), lambda mesh: None, samples=100, seed=2, workers=1)
    report = json.loads(render_report(matrix))
    assert report["samples"] == 100 and report["seed"] == 2
    assert sum(report["counts"].values()) == len(report["pairs"])
    sampled = [p for p in report["pairs"] if p["reason"] != "Adjacent"]
    assert all(p["fraction"] == p["collisions"] / 100 for p in sampled)
    assert report["default_configuration"]["hand_joint"] == pytest.approx(0.15)
