"""Approximate convex decomposition with CoACD, deterministic (fixed seed, one thread).

CoACD is native code that can abort or stall on bad input: callers run this inside a
worker process with a timeout (see worker.py) after validating the mesh. Each returned hull
is re-hulled with qhull so that every part is convex and wound outward whatever CoACD's
own tolerance did.
"""

from __future__ import annotations

import os

import numpy as np

from robotdesc.collision.hull import convex_hull
from robotdesc.collision.result import MeshPart
from robotdesc.errors import NoVolumeError


def coacd_decompose(vertices: np.ndarray, faces: np.ndarray, *, threshold: float,
                    max_hulls: int, hull_vertices: int, iterations: int,
                    preprocess_resolution: int, seed: int, depth: int = 3,
                    nodes: int = 20) -> list[MeshPart]:
    """Convex pieces approximating a mesh (m).

    Args:
        threshold: CoACD's concavity threshold (0.01 .. 1).
        max_hulls: hull count limit (-1: none).
        hull_vertices: CoACD simplifies every hull to at most this many vertices.
        iterations: Monte Carlo tree search iterations.
        depth: Monte Carlo tree search depth (cuts looked ahead).
        nodes: Monte Carlo tree search nodes (candidate cuts per level).
        preprocess_resolution: voxel resolution of the manifold pre-processing.
        seed: random seed.

    Raises:
        ImportError: coacd is not installed (it is a dependency of robotdesc: reinstall robotdesc).
        NoVolumeError: CoACD returned nothing with volume.
    """
    os.environ.setdefault("OMP_NUM_THREADS", "1")  # before libgomp loads: jobs parallelise
    import coacd

    coacd.set_log_level("error")
    mesh = coacd.Mesh(np.ascontiguousarray(vertices, dtype=np.float64),
                      np.ascontiguousarray(faces, dtype=np.int32))
    pieces = coacd.run_coacd(mesh, threshold=float(threshold), max_convex_hull=int(max_hulls),
                             preprocess_mode="auto",
                             preprocess_resolution=int(preprocess_resolution),
                             mcts_iterations=int(iterations), mcts_max_depth=int(depth),
                             mcts_nodes=int(nodes), merge=True, decimate=True,
                             max_ch_vertex=int(hull_vertices), seed=int(seed))
    parts = []
    for piece_vertices, _ in pieces:
        try:
            parts.append(convex_hull(np.asarray(piece_vertices, dtype=np.float64)))
        except NoVolumeError:
            continue  # a flat sliver of a piece: nothing to collide with
    if not parts:
        raise NoVolumeError("CoACD returned no piece with volume")
    return parts
