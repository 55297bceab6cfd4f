"""Real-time factor of the Engineer in MuJoCo: visual meshes as collision vs generated collision.

The Engineer papers (docs/engineer sources, Table II of the second paper) measured a
real-time factor of about 0.2 in Gazebo with the visual meshes used for collision, against
about 1 with simple collision meshes: a ratio of about 5. This script measures the same two
set-ups on robotdesc's Engineer model, in MuJoCo, in the same run and the same scene (the
settle test: dropped on a plane, joints held at neutral, 212 track wheels):
1. "visual": every link's `<visual>` meshes used as its collision geometry;
2. "generated": `robotdesc.generate_collision` output (method from --method);
and also the collision geometry as written in the package. It prints each RTF, the ratio
generated / visual beside the paper's 0.2 vs 1, the settle test result, and the times spent
building the scenes (mesh conversion and MuJoCo's convex hulls) and generating collision.

Run: python benchmarks/bench_sim.py [--seconds S] [--method decimate|hull|coacd|...]
     [--self-collision] [FILE]
Needs the sim extra (pip install "robotdesc[sim]").
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
ENGINEER = REPO / "robots/engineer_description/urdf/engineer.urdf.xacro"
PAPER_VISUAL_RTF, PAPER_SIMPLE_RTF = 0.2, 1.0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file", nargs="?", default=str(ENGINEER))
    parser.add_argument("--seconds", type=float, default=2.0, help="simulated s per run")
    parser.add_argument("--min-wall", type=float, default=2.0,
                        help="repeat each run until this many wall seconds were spent")
    parser.add_argument("--method", default="decimate", help="generate_collision method")
    parser.add_argument("--self-collision", action="store_true",
                        help="let links collide with each other (Gazebo selfCollide true)")
    ns = parser.parse_args(argv)
    sys.path.insert(0, str(REPO / "src"))

    from robotdesc.sim.convert import SceneOptions
    from robotdesc.sim.load import load_sim_input
    from robotdesc.sim.rtf import measure_rtf
    from robotdesc.sim.run import SimOptions, scene_for, settle_robot
    from robotdesc.sim.settle import SettleOptions

    loaded = load_sim_input(ns.file)
    options = SimOptions(settle=SettleOptions(seconds=ns.seconds),
                         scene=SceneOptions(self_collision=ns.self_collision),
                         generate_method=ns.method)
    robot = loaded.robot
    print(f"{robot.name}: {len(robot.links)} links, {len(robot.joints)} joints; "
          f"{ns.seconds:g} s simulated per run, self-collision "
          f"{'on' if ns.self_collision else 'off'}")
    results = {}
    for label in ("visual", "as-is", "generated"):
        started = time.perf_counter()
        scene = scene_for(robot, loaded.meshes, options, label)
        built = time.perf_counter() - started
        measured = measure_rtf(scene, label, ns.seconds, options.settle.hold, ns.min_wall)
        results[label] = measured
        print(f"  collision {label:<10} RTF {measured.rtf:9.2f}   {measured.geoms:4d} geoms, "
              f"{measured.mesh_vertices:8d} mesh vertices (hulls); scene built in "
              f"{built:6.1f} s")
    ratio = results["generated"].rtf / results["visual"].rtf
    paper = PAPER_SIMPLE_RTF / PAPER_VISUAL_RTF
    print(f"  ratio generated / visual: {ratio:.2f}   (paper, Gazebo: {PAPER_SIMPLE_RTF:g} / "
          f"{PAPER_VISUAL_RTF:g} = {paper:.0f}; aim >= 5)")
    report = settle_robot(robot, loaded.meshes, options)
    print(f"  settle test (collision as written): {'PASS' if report.passed else 'FAIL'}, "
          f"settle time {report.settle_time if report.settle_time is not None else 'none'} s, "
          f"{report.simulated:.1f} s simulated in {report.wall:.2f} s")
    for check in report.failures:
        print(f"    FAIL {check.name}: {check.message}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
