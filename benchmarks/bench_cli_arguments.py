"""How fast a misspelt xacro argument is refused: `robotdesc lint engineer.urdf.xacro
with_griper:=false` (exit 2, before any lint) against `robotdesc --version` (the start-up
alone) and a warm lint of the same file with the right argument, in the same run.

    python benchmarks/bench_cli_arguments.py [--repeat N]
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time
from pathlib import Path

ENGINEER = Path(__file__).resolve().parents[1] / "robots" / "engineer_description" / "urdf" / \
    "engineer.urdf.xacro"


def _time(argv: list[str], expect: int, repeat: int) -> float:
    """The median wall time (s) of `robotdesc ARGV`, checking its exit code."""
    times = []
    for _ in range(repeat):
        started = time.perf_counter()
        done = subprocess.run([sys.executable, "-m", "robotdesc", *argv], capture_output=True,
                              text=True)
        times.append(time.perf_counter() - started)
        assert done.returncode == expect, (argv, done.returncode, done.stderr[-500:])
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeat", type=int, default=5)
    repeat = parser.parse_args().repeat
    startup = _time(["--version"], 0, repeat)
    refused = _time(["lint", str(ENGINEER), "with_griper:=false"], 2, repeat)
    _time(["lint", "-q", str(ENGINEER), "with_gripper:=false"], 0, 1)  # warm the caches
    warm = _time(["lint", "-q", str(ENGINEER), "with_gripper:=false"], 0, repeat)
    print(f"robotdesc --version:                      {startup:6.2f} s")
    print(f"lint ... with_griper:=false (exit 2):     {refused:6.2f} s "
          f"({refused / startup:.1f} x start-up; aim: under 2 s)")
    print(f"lint ... with_gripper:=false (warm lint): {warm:6.2f} s "
          f"(the refusal takes {refused / warm:.2f} of it)")


if __name__ == "__main__":
    main()
