"""A fleet lint: many description packages at once, `--jobs 2` on this machine against the
same targets on a Dask cluster (`--scheduler local --jobs 2`, or `--scheduler ADDRESS`).

Both are whole `robotdesc lint FOLDER... --no-cache` processes (cold: every target expanded and
linted), timed once each in this run; printed: targets, wall time, targets per minute, and
whether the two reports (JSON, sorted) are identical. On one 2-core machine a local Dask
cluster cannot be faster than `--jobs 2` (it adds a scheduler and a process per task); the
point of the cluster is adding machines: point --scheduler at one whose workers see the same
paths (docs/ci.md, "A fleet on Dask").

Usage: python benchmarks/bench_fleet.py [--scheduler ADDRESS] [FOLDER ...]
  default folders: the Engineer and, when extracted (benchmarks/corpus/run_corpus.py), the
  Franka, ANYmal C and Universal Robots corpus repositories under /work/corpus.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
CORPUS = Path("/work/corpus")
DEFAULT = [REPO / "robots" / "engineer_description",
           CORPUS / "frankaemika+franka_description", CORPUS / "ANYbotics+anymal_c_simple_description",
           CORPUS / "ros-industrial+universal_robot"]


def lint(folders: list[str], extra: list[str], env: dict[str, str]) -> tuple[float, dict]:
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "robotdesc", "lint", "-q", "--no-cache",
                           "--format", "json", *folders, *extra], env=env, capture_output=True,
                          text=True, check=False)
    elapsed = time.perf_counter() - start
    if done.returncode not in (0, 1, 2):
        raise SystemExit(f"lint failed ({done.returncode}): {done.stderr[-2000:]}")
    return elapsed, json.loads(done.stdout)


def _comparable(report: dict) -> str:
    return json.dumps({k: v for k, v in report.items() if k not in ("elapsed", "duration")},
                      sort_keys=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folders", nargs="*")
    parser.add_argument("--scheduler", default="local")
    options = parser.parse_args()
    folders = options.folders or [str(f) for f in DEFAULT if f.is_dir()]
    with tempfile.TemporaryDirectory() as scratch:
        env = dict(os.environ, ROBOTDESC_CACHE_DIR=str(Path(scratch) / "cache"),
                   PYTHONPYCACHEPREFIX=str(Path(scratch) / "pycache"))
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        local_s, local = lint(folders, ["--jobs", "2"], env)
        dask_s, remote = lint(folders, ["--jobs", "2", "--scheduler", options.scheduler], env)
    summary = local["summary"]
    targets = summary["files_checked"] + summary["files_not_checked"]
    print(f"folders: {', '.join(Path(f).name for f in folders)}")
    print(f"targets: {targets}")
    for label, seconds in (("--jobs 2 (baseline)", local_s),
                           (f"--scheduler {options.scheduler} --jobs 2", dask_s)):
        print(f"  {label:36s} {seconds:7.1f} s  {60 * targets / seconds:6.1f} targets/min")
    print(f"  reports identical: {_comparable(local) == _comparable(remote)}")


if __name__ == "__main__":
    main()
