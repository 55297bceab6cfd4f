"""Parse + all structural rules, in process, on large inputs.

Figures (best of N, CPU time): a generated 212-wheel rover (each wheel with a mesh visual,
a transmission and Gazebo tags), and the largest example-robot-data URDFs. Baseline, same
run: lxml's own parse of the same bytes (the floor any strict parser pays).

Usage: python benchmarks/bench_parse_rules.py [--repeat N]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from lxml import etree

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "rules"))
from test_large_robot import lint_all, many_wheeled_robot  # noqa: E402

from robotdesc.model.parse import parse_urdf  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from support import example_robot_data_dir  # noqa: E402


def best_of(repeat: int, work) -> float:
    best = float("inf")
    for _ in range(repeat):
        start = time.process_time()
        work()
        best = min(best, time.process_time() - start)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=5)
    repeat = parser.parse_args().repeat
    cases = [("rover, 212 wheels (generated)", many_wheeled_robot(212))]
    robots = example_robot_data_dir()
    for path in sorted(robots.rglob("*.urdf") if robots else (), key=lambda p: p.stat().st_size)[-3:]:
        cases.append((path.name, path.read_bytes()))
    print(f"{'input':34s} {'lxml parse':>11s} {'parse':>9s} {'parse+rules':>12s} {'ratio to lxml':>14s}")
    for name, data in cases:
        floor = best_of(repeat, lambda: etree.fromstring(data))
        parse = best_of(repeat, lambda: parse_urdf(data, name))
        full = best_of(repeat, lambda: lint_all(data))
        print(f"{name:34s} {floor * 1e3:9.1f}ms {parse * 1e3:7.1f}ms {full * 1e3:10.1f}ms {full / floor:13.1f}x")


if __name__ == "__main__":
    main()
