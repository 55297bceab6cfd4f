"""Expansion + lint of a large xacro against the plain `xacro` command on the same file.

Input: benchmarks/data/crawler_212.urdf.xacro, a crawler whose 212 imaginary track wheels are
made by a linearly recursive macro (the form whose xacro expansion time grows super-linearly
with depth). Every figure is the median wall time of whole processes, measured in this run:

- baseline: `xacro FILE` (the PyPI xacro command, output to /dev/null);
- cold:     `robotdesc lint FILE --no-cache` (worker start, expansion, parse, all rules);
- warm:     `robotdesc lint FILE` with the expansion cache already filled.

Aims (issue 2): cold <= 1.5 x baseline; warm <= 0.25 x baseline.

With --scaling, also the cold figures at 56, 112 and 224 wheels per track (one run each):
plain xacro's time grows super-linearly with recursion depth (minidom's insertBefore searches
the parent's child list for every moved node); robotdesc's worker splices in linear time.

Usage: python benchmarks/bench_expand_lint.py [--repeat N] [--scaling] [FILE] [name:=value ...]
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
DEFAULT_INPUT = HERE / "data" / "crawler_212.urdf.xacro"


def wall_time(command: list[str], env: dict[str, str], ok_codes=(0, 1)) -> float:
    start = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env)
    elapsed = time.perf_counter() - start
    if done.returncode not in ok_codes:
        raise SystemExit(f"{' '.join(command)} failed ({done.returncode}):\n{done.stderr.decode()}")
    return elapsed


def median_time(command: list[str], env: dict[str, str], repeat: int) -> float:
    return statistics.median(wall_time(command, env) for _ in range(repeat))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("file", nargs="?", default=str(DEFAULT_INPUT))
    parser.add_argument("args", nargs="*", help="xacro arguments name:=value")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--scaling", action="store_true", help="also time 56/112/224 wheels per track")
    options = parser.parse_args()

    xacro_cli = shutil.which("xacro")
    baseline_cmd = [xacro_cli] if xacro_cli else [sys.executable, "-c",
                                                  "import sys, xacro; sys.argv[0]='xacro'; xacro.main()"]
    baseline_cmd += [options.file, *options.args]
    lint_cmd = [sys.executable, "-m", "robotdesc", "lint", options.file, *options.args]
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, ROBOTDESC_CACHE_DIR=cache)
        baseline = median_time(baseline_cmd, env, options.repeat)
        cold = median_time(lint_cmd + ["--no-cache"], env, options.repeat)
        wall_time(lint_cmd, env)  # fill the cache
        warm = median_time(lint_cmd, env, options.repeat)
    print(f"input: {options.file} {' '.join(options.args)}")
    print(f"{'xacro CLI (baseline)':32s} {baseline:8.3f} s")
    print(f"{'robotdesc lint, cold':32s} {cold:8.3f} s   ratio {cold / baseline:5.2f}  (aim <= 1.50)")
    print(f"{'robotdesc lint, warm cache':32s} {warm:8.3f} s   ratio {warm / baseline:5.2f}  (aim <= 0.25)")
    if options.scaling:
        print(f"\n{'wheels per track':>16s} {'xacro':>9s} {'robotdesc cold':>15s} {'ratio':>6s}")
        for wheels in (56, 112, 224):
            args = [f"main_wheels:={wheels}", f"flipper_wheels:={wheels}"]
            plain = wall_time(baseline_cmd + args, env)
            ours = wall_time(lint_cmd + args + ["--no-cache"], env)
            print(f"{wheels:16d} {plain:8.2f}s {ours:14.2f}s {ours / plain:6.2f}")


if __name__ == "__main__":
    main()
