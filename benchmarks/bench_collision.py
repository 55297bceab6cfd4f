"""Collision generation on a whole example-robot-data robot: per method, polygons before and
after (the Engineer paper's hand-made ratio was about 170:1), fidelity, wall time with 1 and
2 jobs, and the cached re-run. The decimation baseline is the other engine,
fast-simplification, on the same robot in the same run.

    python benchmarks/bench_collision.py [ROBOT] [--methods decimate,hull,...] [--jobs 2]

ROBOT: a description file, or a path relative to example-robot-data's robots/ (default UR5).
A method spec `decimate/ENGINE` picks the decimator, a `+fixed` suffix turns `adapt` off
(the old defaults: a fixed budget, hulls over the engine's vertex limit kept); the `links
with findings` column counts links that would make `robotdesc collision` exit 1.

Aims (issue 4): decimation of a whole robot < 2 s; cached re-run < 0.5 s; `--jobs 2` at
least 1.7x faster than `--jobs 1` on CoACD.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

DEFAULT_ROBOT = "ur_description/urdf/ur5_robot.urdf"


def main() -> None:
    import robotdesc
    from robotdesc.collision.worker import run_tasks
    from support import example_robot_data_dir

    parser = argparse.ArgumentParser()
    parser.add_argument("robot", nargs="?", default=DEFAULT_ROBOT)
    parser.add_argument("--methods",
                        default="auto,decimate,decimate/fast-simplification,hull,primitive,"
                                "coacd",
                        help="methods; decimate/ENGINE picks the decimator")
    parser.add_argument("--jobs", default="1,2",
                        help="job counts timed, comma-separated (default 1,2)")
    parser.add_argument("--dask", action="store_true",
                        help="also time each method on a local Dask cluster of 2 worker "
                             "processes (robotdesc[dask]) against --jobs 2")
    ns = parser.parse_args()
    robots = example_robot_data_dir()
    if robots is None:
        sys.exit("example-robot-data is not installed")
    given = Path(ns.robot)
    robot = robotdesc.load(str(given if given.is_file() else robots / ns.robot))
    job_counts = [int(j) for j in ns.jobs.split(",")]
    package_map = [("example-robot-data", str(robots.parent))]
    print(f"robot: {ns.robot} ({len(robot.links)} links)")
    run_tasks(abs, [1], jobs=1, timeout_s=60)  # start the worker server before timing
    print(f"{'method':29} {'faces before':>12} {'after':>7} {'ratio':>7} {'hulls':>5} "
          f"{'mean H%':>8} {'max H%':>7} {'jobs=1 s':>9} {'jobs=2 s':>9} {'speedup':>7} "
          f"{'cached s':>9} {'findings':>8} failed")
    for spec in ns.methods.split(","):
        name, fixed, _ = spec.partition("+fixed")
        method, _, engine = name.partition("/")
        extra = {"decimator": engine} if engine else {}
        if fixed:
            extra["adapt"] = False
        times = {jobs: float("nan") for jobs in (1, 2)}
        cached = float("nan")
        for jobs in job_counts:
            with tempfile.TemporaryDirectory() as cache:
                start = time.perf_counter()
                result = robotdesc.generate_collision(robot, method, jobs=jobs,
                                                      package_map=package_map,
                                                      cache_dir=cache, **extra)
                times[jobs] = time.perf_counter() - start
                if jobs == job_counts[-1]:
                    start = time.perf_counter()
                    again = robotdesc.generate_collision(robot, method, jobs=jobs,
                                                         package_map=package_map,
                                                         cache_dir=cache, **extra)
                    cached = time.perf_counter() - start
                    assert all(o.report.cached for o in again.outcomes if o.written)
        totals = result.totals()
        written = [o.report for o in result.outcomes if o.written]
        percents = [r.percent(r.hausdorff) for r in written]
        mean = sum(percents) / len(percents) if percents else float("nan")
        worst = max(percents) if percents else float("nan")
        ratio = f"{totals['reduction']:.0f}:1" if totals["reduction"] else "-"
        failed = [o.report.link for o in result.outcomes if not o.written]
        flagged = sum(1 for o in result.outcomes
                      if any(f.severity in ("warning", "error") for f in o.report.findings))
        print(f"{spec:29} {totals['faces_before']:>12} {totals['faces_after']:>7} "
              f"{ratio:>7} {totals['hulls']:>5} {mean:>8.2f} {worst:>7.2f} {times[1]:>9.2f} "
              f"{times[2]:>9.2f} {times[1] / times[2]:>7.2f} {cached:>9.2f} {flagged:>8} "
              f"{','.join(failed) or '-'}")
        if ns.dask:
            seconds = _on_local_cluster(robotdesc, robot, method, package_map, extra)
            print(f"{'':29} on a local Dask cluster (2 workers): {seconds:.2f} s, "
                  f"{seconds / times[2]:.2f}x the --jobs 2 time")


def _on_local_cluster(robotdesc, robot, method: str, package_map, extra: dict) -> float:
    """Wall time of one uncached run on a fresh local Dask cluster (started before timing)."""
    from distributed import LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, \
            tempfile.TemporaryDirectory() as cache:
        start = time.perf_counter()
        robotdesc.generate_collision(robot, method, package_map=package_map, cache_dir=cache,
                                     scheduler=cluster.scheduler_address, **extra)
        return time.perf_counter() - start


if __name__ == "__main__":
    main()
