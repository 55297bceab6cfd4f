"""robotdesc's own convex hull (robotdesc.mesh.hull, numpy) against scipy's qhull on the
corpus' meshes (issue 31, item 3: a cold lint no longer imports scipy).

For every mesh of the corpus whose mass properties come from its convex hull (open and
misoriented surfaces; `--all`: every mesh), both hulls of its merged vertices are built and
their mass properties (density 1) compared. Printed: the meshes' count, the summed, median and
slowest times of both (in this process, scipy already imported; the slowest of the five
slowest timed again, best of 3), the largest relative
differences (volume; centre of mass over the bounding box's largest side; inertia over the
largest entry of scipy's), and, on its own line, what importing scipy.spatial costs in a
fresh interpreter that has numpy already (CPU and wall, median of 5): the time a cold lint
saved by not importing it.

Usage: python benchmarks/bench_hull.py [--corpus DIR] [--all] [--only SUBSTR]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from scipy.spatial import ConvexHull, QhullError

from robotdesc.mesh.errors import MeshError
from robotdesc.mesh.health import merge_vertices
from robotdesc.mesh.hull import convex_hull_faces
from robotdesc.mesh.load import load_mesh
from robotdesc.mesh.mass import MassProperties, volume_integrals
from robotdesc.mesh.records import MassMethod
from robotdesc.mesh.summary import summarize

SUFFIXES = (".stl", ".dae", ".obj")
IMPORT_SCIPY = ("import numpy, time; c, w = time.process_time(), time.perf_counter(); "
                "import scipy.spatial; "
                "print(time.process_time() - c, time.perf_counter() - w)")


def scipy_faces(points: np.ndarray) -> np.ndarray | None:
    """qhull's triangles wound outward, or None where qhull finds no volume."""
    try:
        hull = ConvexHull(points)
    except (QhullError, ValueError):
        return None
    faces = hull.simplices.copy()
    soup = points[faces]
    normal = np.cross(soup[:, 1] - soup[:, 0], soup[:, 2] - soup[:, 0])
    inward = np.einsum("ij,ij->i", normal, hull.equations[:, :3]) < 0
    faces[inward] = faces[inward][:, ::-1]
    return faces


def properties(points: np.ndarray, faces: np.ndarray | None) -> MassProperties | None:
    if faces is None:
        return None
    integrals = volume_integrals(points[faces])
    return integrals.properties() if integrals.volume > 0 else None


def differences(ours: MassProperties, theirs: MassProperties, points: np.ndarray
                ) -> tuple[float, float, float]:
    """Relative differences: volume, centre of mass (over the largest side), inertia."""
    side = float(np.ptp(points, axis=0).max())
    volume = abs(ours.volume - theirs.volume) / theirs.volume
    centre = float(np.abs(np.subtract(ours.center_of_mass, theirs.center_of_mass)).max()) / side
    inertia_ref = float(np.abs(theirs.inertia).max())
    inertia = float(np.abs(np.subtract(ours.inertia, theirs.inertia)).max()) / inertia_ref
    return volume, centre, inertia


def retimed(name: str) -> tuple[float, float, str]:
    """Ours and scipy's best of 3 on one mesh (a single timing can catch a pause of the
    machine), and its name with its point count."""
    points = merge_vertices(load_mesh(name).triangles)[0]
    ours, theirs = [], []
    for _ in range(3):
        start = time.perf_counter()
        convex_hull_faces(points)
        ours.append(time.perf_counter() - start)
        start = time.perf_counter()
        scipy_faces(points)
        theirs.append(time.perf_counter() - start)
    return min(ours), min(theirs), f"{name} ({len(points)} points)"


def import_cost(repeat: int = 5) -> tuple[float, float]:
    """Median CPU and wall seconds of `import scipy.spatial` in a fresh interpreter."""
    cpu, wall = [], []
    for _ in range(repeat):
        done = subprocess.run([sys.executable, "-c", IMPORT_SCIPY], capture_output=True,
                              text=True, check=True)
        c, w = (float(v) for v in done.stdout.split())
        cpu.append(c)
        wall.append(w)
    return statistics.median(cpu), statistics.median(wall)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--corpus", type=Path, default=Path("/work/corpus"))
    parser.add_argument("--all", action="store_true", help="every mesh, not only those "
                        "whose mass properties come from the hull")
    parser.add_argument("--only", default="", help="paths containing this")
    args = parser.parse_args()
    meshes = sorted(str(path) for path in args.corpus.rglob("*")
                    if path.suffix.lower() in SUFFIXES and args.only in str(path)
                    and path.is_file())
    count = 0
    ours_times: list[float] = []
    theirs_times: list[float] = []
    ours_total = theirs_total = 0.0
    timed: list[tuple[float, str]] = []
    worst = [0.0, 0.0, 0.0]
    worst_mesh = ["", "", ""]
    disagree = []
    for name in meshes:
        try:
            mesh = load_mesh(name)
        except (MeshError, OSError, ValueError):
            continue
        if not args.all and summarize(mesh).method is not MassMethod.CONVEX_HULL:
            continue
        points = merge_vertices(mesh.triangles)[0]
        start = time.perf_counter()
        faces = convex_hull_faces(points)
        ours_time = time.perf_counter() - start
        start = time.perf_counter()
        reference = scipy_faces(points)
        theirs_time = time.perf_counter() - start
        count += 1
        ours_times.append(ours_time)
        theirs_times.append(theirs_time)
        ours_total += ours_time
        theirs_total += theirs_time
        timed.append((ours_time, name))
        ours, theirs = properties(points, faces), properties(points, reference)
        if ours is None or theirs is None:
            if (ours is None) != (theirs is None):
                disagree.append(name)
            continue
        for i, value in enumerate(differences(ours, theirs, points)):
            if value > worst[i]:
                worst[i], worst_mesh[i] = value, name
    print(f"meshes: {count} ({'all' if args.all else 'convex-hull fallback'}) of "
          f"{len(meshes)} under {args.corpus}")
    print(f"hull time, all meshes: ours {ours_total:.3f} s, scipy {theirs_total:.3f} s "
          f"(ratio {ours_total / max(theirs_total, 1e-9):.2f})")
    if count:
        print(f"median per mesh: ours {statistics.median(ours_times) * 1e3:.1f} ms, scipy "
              f"{statistics.median(theirs_times) * 1e3:.1f} ms")
    slowest = max((retimed(name) for _, name in sorted(timed)[-5:]), default=None)
    if slowest is not None:
        print(f"slowest mesh (ours, best of 3): {slowest[0] * 1e3:.1f} ms, scipy "
              f"{slowest[1] * 1e3:.1f} ms: {slowest[2]}")
    for label, value, name in zip(("volume", "centre of mass", "inertia"), worst, worst_mesh):
        where = os.path.relpath(name, args.corpus) if name else ""
        print(f"max relative difference, {label}: {value:.2e} {where}")
    print(f"one has a hull and the other none: {len(disagree)} {disagree[:5]}")
    cpu, wall = import_cost()
    print(f"import scipy.spatial in a fresh interpreter (numpy imported): "
          f"cpu {cpu:.3f} s, wall {wall:.3f} s (median of 5)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
