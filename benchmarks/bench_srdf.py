"""Time the self-collision matrix: wall and CPU time (this process and its workers) for a
7-dof arm (Panda with hand, from example-robot-data), a synthetic 30-link robot with convex
(box) collision geometry, and the Engineer (246 links, 212 wheels) when present.

Run: python benchmarks/bench_srdf.py [--samples 10000] [--workers 2] [--all-samples]
Aims: 10,000 samples of the 30-link convex robot in under 20 s on 2 cores; the Engineer in
under 30 s (issue 18; before: 619 s wall, nothing printed, checking every pair in every sample).
On a shared machine the wall time is noisy: the CPU time is the steadier figure.
"""

from __future__ import annotations

import argparse
import os
import resource
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))

import robotdesc  # noqa: E402
from robotdesc.mesh.locate import MeshLocator  # noqa: E402
from robotdesc.model.parse import parse_urdf  # noqa: E402
from robotdesc.srdf import compute_matrix  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from support import example_robot_data_dir  # noqa: E402

ROBOTS = example_robot_data_dir() or Path("example-robot-data-not-installed")
ENGINEER = REPO / "robots/engineer_description/urdf/engineer.urdf.xacro"
TARGET_S = 20.0
#: The Engineer before issue 18 (10,000 samples, 2 workers, every pair in every sample).
ENGINEER_BEFORE_S = 619.0
ENGINEER_TARGET_S = 30.0


def snake(links: int = 30) -> str:
    """A chain of `links` boxes on alternating-axis revolute joints (convex geometry only)."""
    inertia = '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>'
    parts = ['<robot name="snake30">']
    for i in range(links):
        parts.append(f'<link name="l{i}"><inertial><mass value="1"/>{inertia}</inertial>'
                     '<collision><origin xyz="0 0 0.05"/><geometry><box size="0.06 0.06 0.09"/>'
                     '</geometry></collision></link>')
        if i:
            axis = "1 0 0" if i % 2 else "0 1 0"
            parts.append(f'<joint name="j{i}" type="revolute"><parent link="l{i - 1}"/>'
                         f'<child link="l{i}"/><origin xyz="0 0 0.1"/><axis xyz="{axis}"/>'
                         '<limit lower="-1.2" upper="1.2" effort="1" velocity="1"/></joint>')
    return "\n".join(parts + ["</robot>"])


def cpu_seconds() -> float:
    """CPU time (user + system, s) of this process and its finished children."""
    return sum(u.ru_utime + u.ru_stime for u in (resource.getrusage(resource.RUSAGE_SELF),
                                                 resource.getrusage(resource.RUSAGE_CHILDREN)))


def measure(label: str, robot, mesh_path, samples: int, workers: int,
            adaptive: bool) -> float:
    start, cpu = time.perf_counter(), cpu_seconds()
    matrix = compute_matrix(robot, mesh_path, samples=samples, seed=0, workers=workers,
                            adaptive=adaptive)
    elapsed, cpu = time.perf_counter() - start, cpu_seconds() - cpu
    pairs = sum(1 for p in matrix.pairs if p.samples)
    print(f"{label:28s} links={len(robot.links):3d} pairs={pairs:5d} samples={matrix.samples}"
          f"/{samples} workers={workers}: {elapsed:6.2f} s wall, {cpu:6.2f} s CPU, "
          f"{matrix.samples / elapsed:8.0f} samples/s, {len(matrix.disabled())} disabled")
    return elapsed


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=10000)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--all-samples", action="store_true", help="no adaptive stop")
    ns = parser.parse_args()
    adaptive = not ns.all_samples
    panda = ROBOTS / "panda_description/urdf/panda.urdf"
    if panda.is_file():
        robot = robotdesc.load(str(panda))
        meshes = MeshLocator.for_robot(robot, package_map=(("example-robot-data",
                                                             str(ROBOTS.parent)),),
                                       origin=str(panda))
        measure("panda (7 dof + hand, meshes)", robot, meshes.path, ns.samples,
                ns.workers, adaptive)
    snake_robot = parse_urdf(snake().encode(), "snake30.urdf")
    elapsed = measure("snake30 (30 links, boxes)", snake_robot, lambda mesh: None, ns.samples,
                      ns.workers, adaptive)
    print(f"target: {ns.samples} samples of 30 convex links < {TARGET_S:g} s: "
          f"{'met' if elapsed < TARGET_S else 'NOT met'} ({os.cpu_count()} CPUs here)")
    if ENGINEER.is_file():
        start = time.perf_counter()
        robot = robotdesc.load(str(ENGINEER))
        measure("engineer", robot, MeshLocator.for_robot(robot, origin=str(ENGINEER)).path,
                ns.samples, ns.workers, adaptive)
        elapsed = time.perf_counter() - start  # with loading, as the command
        print(f"engineer with loading: {elapsed:.1f} s wall; before: {ENGINEER_BEFORE_S:g} s "
              f"({ENGINEER_BEFORE_S / elapsed:.0f}x); target < {ENGINEER_TARGET_S:g} s: "
              f"{'met' if elapsed < ENGINEER_TARGET_S else 'NOT met'}")
    else:
        print("engineer: robots/engineer_description not present yet; skipped")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
