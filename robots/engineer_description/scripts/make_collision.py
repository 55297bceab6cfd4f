#!/usr/bin/env python3
"""Generate the Engineer's collision meshes with `robotdesc collision`, or check them.

One output folder per method under meshes/collision/, each with robotdesc's manifest
(robotdesc-collision.json) and the macros `<link>_collision` (engineer.collision.xacro) that
urdf/collision.xacro includes. Which method for which link, and why, is in the README
("Collision geometry"). The chassis, tracks, flippers, sealed connector and imaginary
wheels keep hand-written primitives and are not listed here.

Usage: python scripts/make_collision.py [--check] [--jobs N]
  --check   write nothing; exit 1 when a folder's outputs are missing, edited or stale
            (the same command line with `robotdesc collision --check`)
Needs: robotdesc with its collision extra (CoACD, fast-simplification), PYTHONPATH=src in a
clone of the repository.
"""

from __future__ import annotations

import argparse
import logging
import os
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

from package_properties import PACKAGE

LOG = logging.getLogger("make_collision")
TOP = PACKAGE / "urdf" / "engineer.urdf.xacro"


@dataclass(frozen=True)
class CollisionSet:
    """One `robotdesc collision` run: a method, its options and the links it makes."""

    folder: str                 # relative to the package
    method: str
    options: tuple[str, ...]
    links: tuple[str, ...]

    def arguments(self, check: bool, jobs: int | None = None) -> list[str]:
        """The command line after `robotdesc`."""
        args = ["collision", str(TOP), "--method", self.method, *self.options,
                "--out", str(PACKAGE / self.folder)]
        for link in self.links:
            args += ["--link", link]
        if jobs:
            args += ["--jobs", str(jobs)]
        return args + (["--check"] if check else [])


SETS: tuple[CollisionSet, ...] = (
    # Arm beams and the bracket: non-convex, smooth and closed; quadric decimation keeps
    # their pockets and forks within a millimetre at about 1,600 triangles each.
    CollisionSet("meshes/collision/decimate", "decimate", ("--faces", "1600"),
                 ("waist_link", "shoulder_link", "forearm_link")),
    # The head with its fork, LRF, cameras and mount, and the gripper's parts: convex pieces
    # (CoACD), which every engine collides fast; the jaws' pieces follow their pads, so the
    # closed jaws stay apart.
    CollisionSet("meshes/collision/coacd", "coacd", ("--threshold", "0.08", "--seed", "0",
                                                     "--mesh-timeout", "1800"),
                 ("head_link", "part_one_left", "part_one_right",
                  "part_two_left", "part_two_right", "part_three_left", "part_three_right")),
)


def run(check: bool, jobs: int | None = None) -> int:
    """Run every set (or check it); the worst exit code of `robotdesc collision`."""
    worst = 0
    for item in SETS:
        command = [sys.executable, "-m", "robotdesc", *item.arguments(check, jobs)]
        LOG.info("%s", " ".join(command))
        code = subprocess.run(command, check=False, env=dict(os.environ)).returncode
        if code:
            LOG.warning("%s: robotdesc collision exited with %d", item.folder, code)
        worst = max(worst, code)
    return worst


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true", help="check instead of writing")
    parser.add_argument("--jobs", type=int, default=None, help="worker processes")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    return run(args.check, args.jobs)


if __name__ == "__main__":
    sys.exit(main())
