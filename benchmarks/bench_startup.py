"""Start-up of the commands that read no description, against the bare interpreter.

Every figure is the median wall time of whole processes (`python -m robotdesc ...`, stdout to
/dev/null), measured in this run beside the baseline `python -c pass` (the same interpreter,
its site-packages and the same bytecode setting: a user's normal one, compiled once).

Aim (issue 31): each command at most 2x the bare interpreter.

Usage: python benchmarks/bench_startup.py [--repeat N] [--src DIR ...]
  --src: the robotdesc source folder(s) to time (e.g. an older checkout's src, to compare
         before and after in one run); default: this checkout's src.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
COMMANDS = (["--version"], ["--help"], ["rules"], ["rule", "J101"])


def wall_time(command: list[str], env: dict[str, str]) -> float:
    start = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env)
    elapsed = time.perf_counter() - start
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(command)} failed ({done.returncode}):\n"
                         f"{done.stderr.decode()}")
    return elapsed


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=21)
    parser.add_argument("--src", action="append", default=[])
    options = parser.parse_args()
    sources = options.src or [str(HERE.parent / "src")]
    bare = [sys.executable, "-c", "pass"]
    envs = {src: dict(os.environ, PYTHONPATH=src) for src in sources}
    for src, env in envs.items():  # compile the bytecode once, as an installed package has it
        for words in COMMANDS:
            wall_time([sys.executable, "-m", "robotdesc", *words], env)
    times: dict[tuple[str, str], list[float]] = {}
    for _ in range(options.repeat):  # interleaved: a load change hits every figure alike
        times.setdefault(("", "python -c pass"), []).append(wall_time(bare, dict(os.environ)))
        for src, env in envs.items():
            for words in COMMANDS:
                command = [sys.executable, "-m", "robotdesc", *words]
                times.setdefault((src, " ".join(words)), []).append(wall_time(command, env))
    baseline = statistics.median(times[("", "python -c pass")])
    print(f"{'python -c pass (baseline)':40s} {baseline * 1000:7.1f} ms")
    for src in sources:
        print(f"source: {src}")
        for words in COMMANDS:
            value = statistics.median(times[(src, " ".join(words))])
            print(f"  {'robotdesc ' + ' '.join(words):38s} {value * 1000:7.1f} ms   ratio "
                  f"{value / baseline:5.2f}  (aim <= 2.00)")


if __name__ == "__main__":
    main()
