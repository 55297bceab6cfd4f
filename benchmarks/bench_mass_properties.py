"""Mass properties and STL loading: robotdesc against pymeshlab and trimesh.

On the watertight meshes of example-robot-data (the same meshes, in the same run):
1. mass properties: robotdesc's chunked numpy integral on the loaded triangle soup, against
   pymeshlab's "Compute Geometric Measures" including the transfer of the (already merged)
   vertex and face arrays into MeshLab; prints both rates, the speed ratio and the largest
   relative difference (volume; centre of mass relative to the mesh's bounding-box diagonal;
   inertia relative to its largest entry);
2. STL loading: robotdesc's numpy reader against `trimesh.load` (which merges vertices), and
   against `trimesh.load(process=False)`, on every STL file.

Run: python benchmarks/bench_mass_properties.py [--repeat N]
Needs the bench and test extras (pymeshlab, example-robot-data).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from support import example_robot_data_dir  # noqa: E402


def robots_dir() -> Path:
    root = example_robot_data_dir()
    if root is None:
        sys.exit("example-robot-data is not installed (pip install -e \".[test]\")")
    return root


def best_time(function, repeat: int) -> float:
    """Fastest of `repeat` runs, in seconds."""
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        best = min(best, time.perf_counter() - start)
    return best


def watertight_meshes(root: Path):
    """(path, soup, merged vertices, faces) of every mesh whose surface is a closed
    two-manifold with consistent winding (where MeshLab computes volume), outward-wound."""
    from robotdesc.mesh.health import merge_vertices, mesh_health
    from robotdesc.mesh.load import FORMATS, load_mesh
    from robotdesc.mesh.mass import volume_integrals
    from robotdesc.mesh.validate import MeshError

    found = []
    for path in sorted(p for p in root.rglob("*") if p.suffix.lower().lstrip(".") in FORMATS):
        try:
            soup = load_mesh(path).triangles
        except MeshError:
            continue
        health = mesh_health(soup)
        if health.watertight and health.consistent_winding and health.degenerate_faces == 0:
            if volume_integrals(soup).volume < 0:  # inverted: compare it outward-wound
                soup = soup[:, ::-1].copy()
            vertices, faces = merge_vertices(soup)
            found.append((path, soup, vertices, faces.astype(np.int32)))
    return found


def compare_mass_properties(meshes, repeat: int) -> None:
    import pymeshlab

    from robotdesc.mesh.mass import bounds, volume_integrals

    def ours():
        return [volume_integrals(soup).properties() for _, soup, _, _ in meshes]

    def meshlab():
        results = []
        for _, _, vertices, faces in meshes:
            measured = pymeshlab.MeshSet()
            measured.add_mesh(pymeshlab.Mesh(vertices, faces))
            results.append(measured.get_geometric_measures())
        return results

    ours_time = best_time(ours, repeat)
    meshlab_time = best_time(meshlab, repeat)
    worst = {"volume": (0.0, ""), "center_of_mass": (0.0, ""), "inertia": (0.0, "")}
    for (path, soup, _, _), mine, theirs in zip(meshes, ours(), meshlab(), strict=True):
        if "mesh_volume" not in theirs:
            continue
        size = float(np.linalg.norm(np.subtract(*bounds(soup))))
        inertia = np.asarray(theirs["inertia_tensor"])
        errors = {
            "volume": abs(mine.volume - theirs["mesh_volume"]) / abs(theirs["mesh_volume"]),
            "center_of_mass": float(np.abs(np.subtract(mine.center_of_mass,
                                                       theirs["center_of_mass"])).max()) / size,
            "inertia": float(np.abs(mine.inertia_matrix() - inertia).max()
                             / np.abs(inertia).max()),
        }
        for key, value in errors.items():
            if value >= worst[key][0]:
                worst[key] = (value, path.name)
    triangles = sum(len(soup) for _, soup, _, _ in meshes)
    print(f"mass properties: {len(meshes)} watertight meshes, {triangles} triangles "
          f"(best of {repeat})")
    print(f"  robotdesc  {ours_time * 1e3:9.1f} ms  {triangles / ours_time / 1e6:6.2f} "
          "M triangles/s")
    print(f"  pymeshlab  {meshlab_time * 1e3:9.1f} ms  {triangles / meshlab_time / 1e6:6.2f} "
          "M triangles/s (with transfer)")
    print(f"  speed ratio: {meshlab_time / ours_time:.1f}x")
    for key, (value, name) in worst.items():
        print(f"  largest relative difference, {key}: {value:.2e} ({name})")


def compare_stl_loading(root: Path, repeat: int) -> None:
    import trimesh

    from robotdesc.mesh.stl import read_stl

    files = sorted(p for p in root.rglob("*") if p.suffix.lower() == ".stl")
    triangles = sum(len(read_stl(p)) for p in files)
    ours_time = best_time(lambda: [read_stl(p) for p in files], repeat)
    merged_time = best_time(lambda: [trimesh.load(p) for p in files], repeat)
    raw_time = best_time(lambda: [trimesh.load(p, process=False) for p in files], repeat)
    print(f"STL loading: {len(files)} files, {triangles} triangles (best of {repeat})")
    print(f"  robotdesc numpy reader     {ours_time * 1e3:8.1f} ms")
    print(f"  trimesh.load               {merged_time * 1e3:8.1f} ms  "
          f"({merged_time / ours_time:.1f}x slower)")
    print(f"  trimesh.load(process=False){raw_time * 1e3:8.1f} ms  "
          f"({raw_time / ours_time:.1f}x slower)")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs per timing (best is kept)")
    args = parser.parse_args(argv)
    root = robots_dir()
    if not root.is_dir():
        print("example-robot-data is not installed", file=sys.stderr)
        return 2
    meshes = watertight_meshes(root)
    compare_mass_properties(meshes, args.repeat)
    compare_stl_loading(root, args.repeat)
    return 0


if __name__ == "__main__":
    sys.exit(main())
