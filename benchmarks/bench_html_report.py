"""`robotdesc.html_report` on the Engineer (246 links), as the tutorial calls it (with a
generated hull collision result of two links): the first call in a process (caches on disk
warm) and a second one, against a warm `robotdesc.lint` of the same file in the same run.
Aim (issue 34): under 3 s warm. Prints the slowest functions of the first call with
`--profile`.

    python benchmarks/bench_html_report.py [--profile]
"""

from __future__ import annotations

import argparse
import cProfile
import pstats
import time
from pathlib import Path

import robotdesc

ENGINEER = str(Path(__file__).resolve().parents[1] / "robots" / "engineer_description" / "urdf"
               / "engineer.urdf.xacro")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--profile", action="store_true")
    profile = parser.parse_args().profile
    robotdesc.lint(ENGINEER)  # warm the disk caches (expansion, meshes, rules)
    started = time.perf_counter()
    result = robotdesc.lint(ENGINEER)
    lint_s = time.perf_counter() - started
    collision = robotdesc.generate_collision(result.robot, "hull",
                                             links=["head_link", "left_flipper_link"], jobs=2)
    profiler = cProfile.Profile() if profile else None
    started = time.perf_counter()
    if profiler:
        profiler.enable()
    page = robotdesc.html_report(result, collision)
    if profiler:
        profiler.disable()
    first = time.perf_counter() - started
    started = time.perf_counter()
    robotdesc.html_report(result, collision)
    second = time.perf_counter() - started
    print(f"warm lint (baseline):       {lint_s:6.2f} s")
    print(f"html_report, first call:    {first:6.2f} s ({first / lint_s:.2f} x the lint; "
          f"aim: under 3 s) -> {len(page) / 1e6:.1f} MB")
    print(f"html_report, second call:   {second:6.2f} s ({second / lint_s:.2f} x the lint)")
    if profiler:
        pstats.Stats(profiler).sort_stats("cumulative").print_stats(20)


if __name__ == "__main__":
    main()
