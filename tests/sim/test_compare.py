"""`robotdesc sim --compare`: the papers' table for collision variants, text and JSON."""

from __future__ import annotations

import json

import pytest

from robotdesc.cli import main

from .sim_support import FIXTURES


@pytest.mark.parametrize("name", ["mujoco", "dart"])
def test_compare_prints_every_figure(name, capsys) -> None:
    pytest.importorskip("mujoco" if name == "mujoco" else "dartpy")
    code = main(["sim", str(FIXTURES / "slip_arm.urdf"), "--engine", name, "--compare",
                 "as-is,visual", "--seconds", "0.05", "--format", "json"])
    document = json.loads(capsys.readouterr().out)
    assert code == 0
    compare = document["compare"]
    assert compare["engine"] == name and compare["paper"]["ratio"] == 5
    labels = [v["label"] for v in compare["variants"]]
    assert labels == ["as-is", "visual"]
    for variant in compare["variants"]:
        assert variant["rtf_cpu"] > 0 and variant["rtf_wall"] > 0
        assert variant["collision_per_step_s"] >= 0 and variant["geoms"] > 0
    assert compare["variants"][0]["ratio_to_first"] == 1


def test_compare_text_has_the_papers_ratio(capsys) -> None:
    pytest.importorskip("mujoco")
    assert main(["sim", str(FIXTURES / "slip_arm.urdf"), "--compare", "as-is,visual",
                 "--seconds", "0.05"]) == 0
    out = capsys.readouterr().out
    assert "ratio visual / as-is (RTF by CPU time)" in out
    assert "papers (Gazebo): visual 0.2, simple collision 1: ratio 5" in out
