"""Lint with mesh rules on a 30-link robot carrying about a million STL triangles.

Input (generated in a temporary package): a 30-link serial arm; each link has its own
binary STL (a closed, finely tessellated cylinder, ~33k triangles, ~1.0 M in all) used as
visual and collision geometry, and a declared `<inertial>`. Every figure is the median wall
time of whole processes (`python -m robotdesc lint FILE --ignore K201`), measured in this run:

- cold:       mesh cache and expansion cache empty (every mesh read, validated, measured);
- warm:       caches filled by a previous run (no mesh work: summaries from the cache);
- no meshes:  the same lint with the mesh-reading rules ignored (`--ignore K201,I2,M1,B`).

K201 (self-collision at the default configuration, a kinematics rule) is left out of all
three: it loads every collision mesh into a collision library on each run, outside the mesh
cache, and is measured once on its own for reference. The warm pair is measured twice: with
the other kinematics rules (K101 imports pinocchio, which imports numpy) and without any
(`--ignore K`), where a warm lint should import no numpy at all. The script lists the
modules the warm lint imports beyond the lint without mesh rules (`python -X importtime`).

Aims (issue 3): cold <= 1.5 s; warm <= 0.4 s and <= no-meshes + 10%.

Usage: python benchmarks/bench_lint_meshes.py [--repeat N] [--links N] [--segments N]
"""

from __future__ import annotations

import argparse
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]


def cylinder(radius: float, length: float, segments: int) -> np.ndarray:
    """A closed outward-wound prism around z: 4 * segments triangles."""
    angles = np.linspace(0, 2 * np.pi, segments, endpoint=False)
    ring = np.stack([radius * np.cos(angles), radius * np.sin(angles)], axis=1)
    nxt = np.roll(ring, -1, axis=0)
    low, high = np.full((segments, 1), -length / 2), np.full((segments, 1), length / 2)
    a0, b0 = np.hstack([ring, low]), np.hstack([nxt, low])
    a1, b1 = np.hstack([ring, high]), np.hstack([nxt, high])
    top = np.tile([0.0, 0.0, length / 2], (segments, 1))
    bottom = np.tile([0.0, 0.0, -length / 2], (segments, 1))
    return np.concatenate([np.stack(t, axis=1) for t in
                           ((a0, b0, b1), (a0, b1, a1), (top, a1, b1), (bottom, b0, a0))])


def write_stl(path: Path, triangles: np.ndarray) -> None:
    records = np.zeros(len(triangles), dtype=[("n", "<f4", (3,)), ("v", "<f4", (3, 3)),
                                              ("a", "<u2")])
    records["v"] = triangles
    with open(path, "wb") as out:
        out.write(b"bench".ljust(80, b" ") + len(triangles).to_bytes(4, "little"))
        out.write(records.tobytes())


def build(root: Path, links: int, segments: int) -> tuple[Path, int]:
    package = root / "bench_arm"
    (package / "meshes").mkdir(parents=True)
    (package / "package.xml").write_text(
        "<package format='3'><name>bench_arm</name><version>0.0.0</version></package>")
    radius, length, mass = 0.04, 0.3, 2.0
    moment_side = mass * (3 * radius ** 2 + length ** 2) / 12
    moment_axis = mass * radius ** 2 / 2
    parts, total = ['<?xml version="1.0"?>', '<robot name="bench_arm">', '  <link name="base"/>'], 0
    for i in range(links):
        triangles = cylinder(radius, length, segments)
        total += len(triangles)
        write_stl(package / "meshes" / f"link{i}.stl", triangles)
        mesh = f'<mesh filename="package://bench_arm/meshes/link{i}.stl"/>'
        parts += [f'  <link name="link{i}">',
                  (f'    <inertial><mass value="{mass}"/><inertia ixx="{moment_side:.6g}" ixy="0" '
                   f'ixz="0" iyy="{moment_side:.6g}" iyz="0" izz="{moment_axis:.6g}"/></inertial>'),
                  f"    <visual><geometry>{mesh}</geometry></visual>",
                  f"    <collision><geometry>{mesh}</geometry></collision>", "  </link>",
                  (f'  <joint name="j{i}" type="revolute"><origin xyz="0 0 {length}"/>'
                   f'<parent link="{"base" if i == 0 else f"link{i - 1}"}"/>'
                   f'<child link="link{i}"/><axis xyz="0 1 0"/>'
                   '<limit lower="-1" upper="1" effort="10" velocity="1"/></joint>')]
    parts.append("</robot>")
    urdf = package / "arm.urdf"
    urdf.write_text("\n".join(parts) + "\n")
    return urdf, total


def wall_time(command: list[str], env: dict[str, str]) -> tuple[float, float]:
    """(wall time, CPU time user + system) of one whole process, in seconds."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env,
                          check=False)
    elapsed = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode not in (0, 1):
        sys.exit(f"command failed ({done.returncode}): {' '.join(command)}\n"
                 f"{done.stderr.decode()}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return elapsed, cpu


def imported_modules(command: list[str], env: dict[str, str]) -> set[str]:
    """The modules a process imports, from `python -X importtime` (command[0] is python)."""
    done = subprocess.run([command[0], "-X", "importtime", *command[1:]],
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env,
                          check=False)
    return set(re.findall(r"^import time:\s+\d+ \|\s+\d+ \|\s*(\S+)",
                          done.stderr.decode(), re.MULTILINE))


HEAVY = ("numpy", "trimesh", "scipy", "collada")
MESH_RULES = "I2,M1,B"


def warm_pair(full: list[str], env: dict[str, str], ignore: str, repeat: int) -> dict:
    """Warm lint against the same lint without mesh rules, both ignoring `ignore`,
    interleaved (a shared machine's load hits both alike)."""
    lint = full + ["--ignore", ignore]
    bare = full + ["--ignore", f"{ignore},{MESH_RULES}"]
    warm_runs, bare_runs = [], []
    for _ in range(repeat):
        warm_runs.append(wall_time(lint, env))
        bare_runs.append(wall_time(bare, env))
    extra = sorted(imported_modules(lint, env) - imported_modules(bare, env))
    return {"warm": _medians(warm_runs), "bare": _medians(bare_runs), "extra": extra,
            "heavy": [m for m in extra if m.split(".")[0] in HEAVY],
            "heavy_warm": sorted(m for m in imported_modules(lint, env)
                                 if m.split(".")[0] in HEAVY and "." not in m)}


def _medians(runs: list[tuple[float, float]]) -> tuple[float, float]:
    return statistics.median(w for w, _ in runs), statistics.median(c for _, c in runs)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--links", type=int, default=30)
    parser.add_argument("--segments", type=int, default=8333)
    ns = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        urdf, triangles = build(Path(folder), ns.links, ns.segments)
        env = dict(os.environ, PYTHONPATH=str(REPO / "src"),
                   PYTHONPYCACHEPREFIX=str(Path(folder) / "pycache"))
        env.pop("PYTHONDONTWRITEBYTECODE", None)  # bytecode compiled once, as for a user
        cache = Path(folder) / "cache"
        env["ROBOTDESC_CACHE_DIR"] = str(cache)
        full = [sys.executable, "-m", "robotdesc", "lint", str(urdf)]
        lint = full + ["--ignore", "K201"]
        wall_time(lint, env)  # compiles the bytecode (into the temporary folder)
        cold_runs = []
        for _ in range(ns.repeat):
            shutil.rmtree(cache, ignore_errors=True)
            cold_runs.append(wall_time(lint, env))
        pairs = {"K201": warm_pair(full, env, "K201", ns.repeat),
                 "K": warm_pair(full, env, "K", ns.repeat)}
        with_k201 = wall_time(full, env)
    cold_s, cold_c = _medians(cold_runs)
    print(f"input: {ns.links} links, {triangles} STL triangles; median of {ns.repeat} "
          "whole processes (wall time; CPU time user+sys in brackets)")
    print(f"cold lint (empty caches), --ignore K201:  {cold_s:.3f} s [{cold_c:.3f}]   "
          "aim <= 1.5 s")
    for ignore, pair in pairs.items():
        (warm_s, warm_c), (bare_s, bare_c) = pair["warm"], pair["bare"]
        print(f"--ignore {ignore}:")
        print(f"  warm lint (caches filled):  {warm_s:.3f} s [{warm_c:.3f}]   aim <= 0.4 s")
        print(f"  lint without mesh rules:    {bare_s:.3f} s [{bare_c:.3f}]")
        print(f"  warm / without mesh rules:  {warm_s / bare_s:.3f} [{warm_c / bare_c:.3f}]   "
              "aim <= 1.10")
        print(f"  warm imports {len(pair['extra'])} modules more; numpy/trimesh/scipy among "
              f"them: {', '.join(pair['heavy']) or 'none'}; heavy packages in the warm "
              f"process: {', '.join(pair['heavy_warm']) or 'none'}")
    print(f"warm lint with K201 (1 run): {with_k201[0]:.3f} s [{with_k201[1]:.3f}]")


if __name__ == "__main__":
    main()
