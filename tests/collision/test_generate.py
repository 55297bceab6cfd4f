"""generate_collision and `robotdesc collision` end to end: bad input per link, a crashed
worker, outputs, the manifest, --check, the cache."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
from mesh.builders import write_binary_stl

import robotdesc
from collision.conftest import box_soup, write_urdf
from robotdesc.cli import main
from robotdesc.collision import generate as generate_module
from robotdesc.collision.worker import TaskFailure, run_tasks


def _bad_meshes(root: Path) -> None:
    meshes = root / "meshes"
    (meshes / "empty.stl").write_bytes(b"")
    soup = box_soup()
    soup[0, 0, 0] = np.nan
    write_binary_stl(meshes / "nan.stl", soup)
    (meshes / "index.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
    flat = box_soup((0.1, 0.1, 0.1))
    flat[..., 2] = 0.0
    write_binary_stl(meshes / "flat.stl", flat)


def _statuses(result):
    return {o.report.link: (o.report.status, [f.code for f in o.report.findings])
            for o in result.outcomes}


def test_each_bad_input_is_a_finding_for_its_link(package):
    _bad_meshes(package)
    urdf = write_urdf(package, {"good": "hip.stl", "empty": "empty.stl", "nan": "nan.stl",
                                "index": "index.obj", "flat": "flat.stl", "gone": "none.stl"})
    robot = robotdesc.load(str(urdf))
    result = robotdesc.generate_collision(robot, "hull", jobs=2)
    statuses = _statuses(result)
    assert statuses["good"][0] != "failed"
    for link in ("empty", "nan", "index"):
        assert statuses[link] == ("failed", ["mesh-error"]), statuses[link]
    assert statuses["flat"] == ("failed", ["no-volume"])
    assert statuses["gone"] == ("failed", ["mesh-unresolved"])
    assert result.failed
    assert robot.link("good").collisions[0].geometry.size == (1.0, 1.0, 1.0)  # not mutated


def test_two_links_with_missing_meshes_each_name_their_own(package):
    """Two unresolved links used to share one result (their sources hashed alike), so the
    second was reported with the first one's file."""
    urdf = write_urdf(package, {"a": "missing_a.stl", "b": "missing_b.stl"})
    result = robotdesc.generate_collision(robotdesc.load(str(urdf)), "hull", jobs=1)
    messages = {o.report.link: o.report.findings[0].message for o in result.outcomes}
    assert "missing_a.stl" in messages["a"] and "missing_b.stl" in messages["b"]


def test_a_crashed_worker_is_a_finding_and_the_others_complete(package, monkeypatch):
    from collision import faults

    urdf = write_urdf(package, {"good": "hip.stl", "bad": "leg.stl"})
    monkeypatch.setattr(generate_module, "LINK_RUNNER", faults.crash_on_bad_link)
    result = robotdesc.generate_collision(robotdesc.load(str(urdf)), "hull", jobs=2,
                                          use_cache=False)
    statuses = _statuses(result)
    assert statuses["good"][0] != "failed"
    assert statuses["bad"] == ("failed", ["worker-crashed"])
    message = result.outcomes[1].report.findings[0].message
    assert "SIGSEGV" in message


def test_worker_timeout_exception_and_order():
    from collision import faults

    assert run_tasks(faults.square, [1, 2, 3], jobs=2, timeout_s=30) == [1, 4, 9]
    [failure] = run_tasks(faults.raise_error, [0], jobs=1, timeout_s=30)
    assert isinstance(failure, TaskFailure) and "boom" in failure.message
    [late] = run_tasks(faults.sleep_forever, [0], jobs=1, timeout_s=0.5)
    assert late.kind == "timeout"


def test_cli_writes_outputs_then_check_passes_then_detects_staleness(package, tmp_path,
                                                                     capsys):
    urdf = write_urdf(package, {"hip": "hip.stl", "leg": "leg.stl"})
    out = package / "collision"
    assert main(["collision", str(urdf), "--method", "hull", "--out", str(out),
                 "--limit-hull-vertices", "5000"]) == 0
    written = sorted(p.name for p in (out / "meshes").iterdir())
    assert written == ["hip.stl", "leg.stl"]
    text = (out / "demo.collision.urdf").read_text()
    assert 'filename="package://demo/collision/meshes/hip.stl"' in text
    assert "<box" not in text  # the old collision boxes were replaced
    reloaded = robotdesc.load(str(out / "demo.collision.urdf"))
    assert reloaded.link("hip").collisions[0].geometry.filename.endswith("hip.stl")
    capsys.readouterr()
    args = ["collision", str(urdf), "--method", "hull", "--out", str(out),
            "--limit-hull-vertices", "5000", "--check"]
    assert main(args) == 0
    assert main(args[:-3] + ["--check"]) == 1  # the vertex limit shapes hulls: in the key
    assert main(args[:-1] + ["--method", "decimate", "--check"]) == 1  # other parameters
    assert "parameters changed" in capsys.readouterr().out
    os.utime(package / "meshes" / "leg.stl")
    with open(package / "meshes" / "leg.stl", "ab") as stream:
        stream.write(b"\0")  # a trailing byte changes the content (and its hash)
    assert main(args) == 1
    (out / "meshes" / "hip.stl").unlink()
    assert main(args) == 1
    assert "missing" in capsys.readouterr().out


def test_never_overwrites_a_file_robotdesc_did_not_write(package, capsys):
    urdf = write_urdf(package, {"hip": "hip.stl"})
    out = package / "collision"
    (out / "meshes").mkdir(parents=True)
    (out / "meshes" / "hip.stl").write_bytes(b"mine")
    assert main(["collision", str(urdf), "--method", "hull", "--out", str(out)]) == 2
    assert (out / "meshes" / "hip.stl").read_bytes() == b"mine"
    assert "refusing to overwrite" in capsys.readouterr().err
    assert not any(p.name.startswith(".robotdesc-") for p in out.rglob("*"))
    assert main(["collision", str(urdf), "--method", "hull",
                 "--out", str(package / "meshes")]) == 2  # the source mesh folder


def test_failed_links_leave_no_files_and_exit_one(package):
    _bad_meshes(package)
    urdf = write_urdf(package, {"hip": "hip.stl", "nan": "nan.stl"})
    out = package / "collision"
    assert main(["collision", str(urdf), "--method", "hull", "--out", str(out)]) == 1
    assert sorted(p.name for p in (out / "meshes").iterdir()) == ["hip.stl"]
    assert not any(p.name.startswith(".robotdesc-") for p in out.rglob("*"))
    text = (out / "demo.collision.urdf").read_text()
    assert text.count("<box") == 1  # the failed link keeps its collision


def _folder_state(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


def test_a_rerun_keeps_the_outputs_of_links_it_does_not_make(package, capsys):
    urdf = write_urdf(package, {"hip": "hip.stl", "leg": "leg.stl"})
    out = package / "collision"
    hull = ["--method", "hull", "--limit-hull-vertices", "1000"]
    assert main(["collision", str(urdf), *hull, "--out", str(out)]) == 0
    before = _folder_state(out)
    # only the hip is made (with other parameters): the leg's outputs stay as they were
    assert main(["collision", str(urdf), *hull, "--target", "2", "--link", "hip",
                 "--out", str(out)]) == 0
    after = _folder_state(out)
    assert after["meshes/leg.stl"] == before["meshes/leg.stl"]
    text = after["demo.collision.urdf"].decode()
    assert "collision/meshes/leg.stl" in text and "collision/meshes/hip.stl" in text
    reloaded = robotdesc.load(str(out / "demo.collision.urdf"))
    assert [c.geometry.filename.rsplit("/", 1)[-1] for c in reloaded.link("leg").collisions] \
        == ["leg.stl"]
    capsys.readouterr()
    assert main(["collision", str(urdf), *hull, "--link", "leg", "--out", str(out),
                 "--check"]) == 0  # the kept link is still current for its own parameters
    # the leg's mesh turns bad: the link fails (exit 1), its earlier outputs stay, and
    # --check says they are stale
    soup = box_soup()
    soup[0, 0, 0] = np.nan
    write_binary_stl(package / "meshes" / "leg.stl", soup)
    assert main(["collision", str(urdf), *hull, "--out", str(out)]) == 1
    assert _folder_state(out)["meshes/leg.stl"] == before["meshes/leg.stl"]
    assert "collision/meshes/leg.stl" in (out / "demo.collision.urdf").read_text()
    capsys.readouterr()
    assert main(["collision", str(urdf), *hull, "--out", str(out), "--check"]) == 1
    assert "leg" in capsys.readouterr().out


def test_edited_earlier_outputs_of_a_link_not_made_now_are_never_overwritten(package,
                                                                              capsys):
    urdf = write_urdf(package, {"hip": "hip.stl", "leg": "leg.stl"})
    out = package / "collision"
    hull = ["--method", "hull", "--limit-hull-vertices", "1000"]
    assert main(["collision", str(urdf), *hull, "--out", str(out)]) == 0
    with open(out / "meshes" / "leg.stl", "ab") as stream:
        stream.write(b"\0")  # the user edited it
    before = _folder_state(out)
    assert main(["collision", str(urdf), *hull, "--link", "hip", "--out", str(out)]) == 2
    assert "meshes/leg.stl is missing or was edited" in capsys.readouterr().err
    assert _folder_state(out) == before


def test_second_run_is_served_from_the_cache(package, tmp_path):
    urdf = write_urdf(package, {"hip": "hip.stl", "leg": "leg.stl"})
    robot = robotdesc.load(str(urdf))
    first = robotdesc.generate_collision(robot, "decimate", cache_dir=str(tmp_path / "c"))
    second = robotdesc.generate_collision(robot, "decimate", cache_dir=str(tmp_path / "c"))
    assert [o.report.cached for o in second.outcomes] == [True, True]
    assert [o.report.faces_after for o in second.outcomes] == \
        [o.report.faces_after for o in first.outcomes]
    third = robotdesc.generate_collision(robot, "decimate", cache_dir=str(tmp_path / "c"),
                                         ratio=0.1)
    assert not any(o.report.cached for o in third.outcomes)


def test_primitive_and_coacd_write_urdf_elements(package):
    urdf = write_urdf(package, {"hip": "hip.stl"})
    out = package / "prim"
    main(["collision", str(urdf), "--method", "primitive", "--out", str(out)])
    reloaded = robotdesc.load(str(out / "demo.collision.urdf"))
    geometry = reloaded.link("hip").collisions[0].geometry
    assert type(geometry).__name__ in ("Box", "Cylinder", "Sphere", "Capsule")


def test_usage_errors(package):
    urdf = write_urdf(package, {"hip": "hip.stl"})
    assert main(["collision", str(urdf), "--method", "hull"]) == 2  # no --out
    assert main(["collision", str(urdf), "--ratio", "0", "--out", "x"]) == 2


def test_links_with_the_same_sources_are_made_once(package):
    urdf = write_urdf(package, {"left": "hip.stl", "right": "hip.stl", "leg": "leg.stl"})
    result = robotdesc.generate_collision(robotdesc.load(str(urdf)), "hull", use_cache=False,
                                          jobs=1)
    by_link = {o.report.link: o for o in result.outcomes}
    assert [by_link[name].report.cached for name in ("left", "right", "leg")] == \
        [False, True, False]
    assert by_link["right"].report.faces_after == by_link["left"].report.faces_after
    assert np.array_equal(by_link["right"].parts[0].vertices, by_link["left"].parts[0].vertices)


def test_cli_decimator_choice_is_reported_and_refused_when_unknown(package, capsys):
    import json

    urdf = write_urdf(package, {"hip": "hip.stl"})
    base = ["collision", str(urdf), "--method", "decimate", "--dry-run", "--format", "json",
            "--ratio", "0.1", "--no-adapt"]
    assert main(base + ["--decimator", "fast-simplification"]) in (0, 1)
    [link] = json.loads(capsys.readouterr().out)["links"]
    assert link["faces_after"] <= 0.1 * link["faces_before"] * 1.05 + 4
    assert "fast-simplification" in link["detail"]
    assert main(base) in (0, 1)
    [link] = json.loads(capsys.readouterr().out)["links"]
    assert "meshoptimizer" in link["detail"]
    assert main(base + ["--decimator", "blender"]) == 2
    assert "invalid choice: 'blender'" in capsys.readouterr().err
