"""Real-time factor of the Engineer: visual meshes as collision vs generated collision, in MuJoCo
and in DART, beside the Engineer papers' Gazebo figures.

The papers (001, Table II) measured in Gazebo a real-time factor of about 0.2 with the visual
meshes used for collision, against about 1 with simple collision meshes: a ratio of about 5.
This script times the same two set-ups on robotdesc's Engineer in the same process and the same
scene (dropped on a plane, joints held), for each wheel count asked (default: the package's
212 wheels and the 18/31 per track of 001's conclusion) and each engine:
1. "visual": every link's `<visual>` meshes used as its collision geometry;
2. "generated": `robotdesc.generate_collision` output (method from --method).
It prints triangles collided, RTF by CPU and by wall time, collision time per step, and the
ratio generated / visual (by CPU time) against the papers' 5. MuJoCo collides convex hulls,
so its ratio stays near 1; DART with ODE's collider collides triangles, as Gazebo does.

Run: python benchmarks/bench_sim.py [--engines mujoco,dart] [--wheels 56/50,18/31]
     [--seconds S] [--method decimate|hull|coacd|...] [FILE]
Needs the extras sim (MuJoCo) and dart (pip install '.[sim,dart]').
"""

from __future__ import annotations

import argparse
import logging
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
ENGINEER = REPO / "robots/engineer_description/urdf/engineer.urdf.xacro"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file", nargs="?", default=str(ENGINEER))
    parser.add_argument("--engines", default="mujoco,dart")
    parser.add_argument("--wheels", default="56/50,18/31",
                        help="main/flipper wheels per track, comma-separated set-ups")
    parser.add_argument("--seconds", type=float, default=0.5, help="simulated s per variant")
    parser.add_argument("--method", default="decimate", help="generate_collision method")
    ns = parser.parse_args(argv)
    sys.path.insert(0, str(REPO / "src"))
    logging.basicConfig(level=logging.WARNING, format="%(message)s")

    from robotdesc.commands.sim import _progress_writer, write_comparison
    from robotdesc.sim.compare import compare_variants
    from robotdesc.sim.engine import engine as engine_named
    from robotdesc.sim.load import load_sim_input
    from robotdesc.sim.scene import SceneOptions

    for wheels in ns.wheels.split(","):
        main_wheels, flipper_wheels = wheels.split("/")
        loaded = load_sim_input(ns.file, {"main_track_wheels": main_wheels,
                                          "flipper_track_wheels": flipper_wheels})
        robot = loaded.robot
        print(f"== {robot.name}: {main_wheels} wheels per main track, {flipper_wheels} per "
              f"flipper track ({len(robot.links)} links, {len(robot.joints)} joints)")
        for name in ns.engines.split(","):
            engine = engine_named(name)
            comparison = compare_variants(
                engine, robot, loaded.meshes, ("visual", "generated"),
                SceneOptions(timestep=engine.default_timestep), ns.seconds,
                generate_method=ns.method, progress=_progress_writer(sys.stderr, name))
            write_comparison(sys.stdout, robot.name, comparison)
            sys.stdout.flush()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
