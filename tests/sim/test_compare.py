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
    captured = capsys.readouterr()
    out = captured.out
    assert "collision   triangles primitives   RTF cpu   ratio" in out
    assert "ratio: each variant's RTF by CPU time over the as-is one's" in out
    assert "papers (Gazebo): visual 0.2, simple collision 1: ratio 5x" in out
    assert " 1.00x " in out


def test_compare_says_what_runs_a_line_per_variant_and_per_tenth_of_a_second(capsys):
    """Plain lines on stderr (not a terminal here), as in CI."""
    pytest.importorskip("mujoco")
    assert main(["sim", str(FIXTURES / "slip_arm.urdf"), "--compare", "as-is,visual",
                 "--seconds", "0.2"]) == 0
    err = capsys.readouterr().err.splitlines()
    assert "robotdesc: sim mujoco: variant 1 of 2: as-is, building the scene" in err
    assert "robotdesc: sim mujoco: variant 2 of 2: visual, building the scene" in err
    for label in ("as-is", "visual"):
        ticks = [line for line in err if line.startswith(f"robotdesc: sim mujoco: {label}: ")
                 and " s simulated in " in line]
        assert [line.split(": ")[3].split(" of ")[0] for line in ticks] == ["0.1", "0.2"]
        assert any(line.startswith(f"robotdesc: sim mujoco: {label}: RTF ") for line in err)


def test_dart_warnings_are_caught_counted_and_attributed(capfd):
    """DART's C++ warnings never reach the terminal raw: they are counted per kind and link
    in the table, listed with -v."""
    pytest.importorskip("dartpy")
    assert main(["sim", str(FIXTURES / "slip_arm.urdf"), "--engine", "dart", "--compare",
                 "as-is", "--seconds", "0.02", "-v"]) == 0
    captured = capfd.readouterr()
    assert "\x1b[" not in captured.err and "Inertia.cpp" not in captured.err
    assert "warnings" in captured.out


def test_native_messages_are_counted_per_kind_and_link():
    from robotdesc.sim.native_log import NativeMessages

    messages = NativeMessages({"wheel_1_link": "wheel_1_link", "wheel_2_link": "wheel_2_link",
                               "wheel_1": "wheel_1_link"})
    for line in ("\x1b[1;33mWarning [Body.cpp:12]\x1b[0m body 'wheel_1_link' mass 0.5",
                 "Warning [Body.cpp:12] body 'wheel_2_link' mass 0.25",
                 "Warning [Body.cpp:12] body 'wheel_1_link' mass 0.5",
                 "Warning [Joint.cpp:3] joint wheel_1 has no limit", ""):
        messages.add(line)
    assert messages.total == 4
    first, second = messages.messages()
    assert first.text == "Warning [Body.cpp:#] body '<link>' mass #" and first.count == 3
    assert first.links == (("wheel_1_link", 2), ("wheel_2_link", 1))
    assert second.links == (("wheel_1_link", 1),)
