"""One workspace run over every example-robot-data description, with --jobs 1 and --jobs 2,
cold and with the caches warm; prints the times and the speed-ups.

Input: the robots/ folder of the installed example-robot-data (about 70 URDFs with their
meshes, plus a few top-level xacro files), linted as one directory by
`robotdesc lint ROBOTS --jobs N`, with a config that maps the `example-robot-data` package
name used in its mesh URIs to its folder. Every figure is the median wall time of whole
processes, measured in this run:

- cold: an empty cache directory (expansions and mesh summaries are computed);
- warm: the same command again with the cache filled by a previous run.

Baselines: `--jobs 1` (for the speed-up of `--jobs 2`) and cold (for the warm speed-up).

Usage: python benchmarks/bench_workspace.py [--repeat N] [--robots DIR]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from support import example_robot_data_dir  # noqa: E402

HERE = Path(__file__).resolve().parent
ROBOTS = example_robot_data_dir()


def lint_command(robots: Path, config: Path, jobs: int) -> list[str]:
    return [sys.executable, "-m", "robotdesc", "lint", str(robots), "--config", str(config),
            "--jobs", str(jobs), "--format", "json"]


def wall_time(command: list[str], env: dict[str, str]) -> float:
    start = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env,
                          check=False)
    elapsed = time.perf_counter() - start
    if done.returncode not in (0, 1, 2):
        raise SystemExit(f"{' '.join(command)} failed ({done.returncode}):\n"
                         f"{done.stderr.decode()}")
    return elapsed


def cold_time(command: list[str], env: dict[str, str], repeat: int) -> float:
    times = []
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as cache:
            times.append(wall_time(command, dict(env, ROBOTDESC_CACHE_DIR=cache)))
    return statistics.median(times)


def warm_time(command: list[str], env: dict[str, str], repeat: int) -> float:
    with tempfile.TemporaryDirectory() as cache:
        warm_env = dict(env, ROBOTDESC_CACHE_DIR=cache)
        wall_time(command, warm_env)  # fill the cache
        return statistics.median(wall_time(command, warm_env) for _ in range(repeat))


def workload(command: list[str], env: dict[str, str]) -> str:
    with tempfile.TemporaryDirectory() as cache:
        done = subprocess.run(command, capture_output=True, check=False,
                              env=dict(env, ROBOTDESC_CACHE_DIR=cache))
    summary = json.loads(done.stdout)["summary"]
    findings = summary["error"] + summary["warning"] + summary["info"]
    return (f"{summary['files_checked']} targets checked, {summary['files_not_checked']} not "
            f"checkable, {findings} findings (exit code {done.returncode})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--robots", type=Path, default=ROBOTS)
    options = parser.parse_args()
    if not options.robots.is_dir():
        raise SystemExit(f"no example-robot-data at {options.robots} "
                         "(pip install example-robot-data)")
    src = str(HERE.parent / "src")
    env = dict(os.environ, PYTHONPATH=src + os.pathsep + os.environ.get("PYTHONPATH", ""))
    with tempfile.TemporaryDirectory() as folder:
        config = Path(folder) / "robotdesc.toml"
        config.write_text(f'[packages]\n"example-robot-data" = "{options.robots.parent}"\n')
        print(f"input: {options.robots}")
        print(f"workload: {workload(lint_command(options.robots, config, 1), env)}")
        print(f"cpus: {os.cpu_count()}, repeat: {options.repeat} (median)")
        times = {}
        for jobs in (1, 2):
            command = lint_command(options.robots, config, jobs)
            times[jobs, "cold"] = cold_time(command, env, options.repeat)
            times[jobs, "warm"] = warm_time(command, env, options.repeat)
    for state in ("cold", "warm"):
        one, two = times[1, state], times[2, state]
        print(f"{state:5s}  --jobs 1 {one:7.2f} s   --jobs 2 {two:7.2f} s   "
              f"speed-up {one / two:4.2f}x")
    for jobs in (1, 2):
        print(f"warm vs cold, --jobs {jobs}: {times[jobs, 'cold'] / times[jobs, 'warm']:4.2f}x")


if __name__ == "__main__":
    main()
