"""Make a triangle soup small enough to embed in a page: weld shared vertices, then reduce
the face count when it exceeds a budget.

Reduction is vertex clustering in numpy: linear time and predictable. (Quadric edge collapse
with fast-simplification took 3-6 s per Engineer mesh and missed the budget by 3x; a view
must open in seconds.) Display only: nothing measured is computed from the reduced mesh.
Units are those of the input (m).
"""

from __future__ import annotations

import numpy as np


def weld(triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """An indexed mesh from a (n, 3, 3) soup: exact duplicate vertices merged.

    Returns:
        (vertices (V, 3) float64, faces (n, 3) int64) with degenerate faces dropped.
    """
    corners = np.ascontiguousarray(triangles.reshape(-1, 3), dtype=np.float64)
    keys = corners.view(np.dtype((np.void, corners.dtype.itemsize * 3))).ravel()
    _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    faces = inverse.reshape(-1, 3).astype(np.int64)
    return corners[first], drop_degenerate(faces)


def drop_degenerate(faces: np.ndarray) -> np.ndarray:
    """Faces whose three indices differ."""
    keep = (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) \
        & (faces[:, 0] != faces[:, 2])
    kept: np.ndarray = faces[keep]
    return kept


def cluster(vertices: np.ndarray, faces: np.ndarray, max_faces: int) -> tuple[np.ndarray,
                                                                              np.ndarray]:
    """Vertex clustering: snap vertices to a grid (coarser until under `max_faces`) and merge
    each cell's vertices at their mean. Crude, but dependency-free and linear time."""
    low, high = vertices.min(axis=0), vertices.max(axis=0)
    extent = float(np.max(high - low)) or 1.0
    cells = max(8, int(np.sqrt(max_faces) * 2))
    best = (vertices, faces)
    while cells >= 2:
        index = np.floor((vertices - low) / extent * cells).astype(np.int64)
        _, inverse = np.unique(index, axis=0, return_inverse=True)
        inverse = inverse.ravel()
        merged = np.zeros((inverse.max() + 1, 3))
        np.add.at(merged, inverse, vertices)
        merged /= np.bincount(inverse)[:, None]
        reduced = _unique_faces(drop_degenerate(inverse[faces]))
        best = (merged, reduced)
        if len(reduced) <= max_faces:
            break
        cells = min(cells - 1, int(cells * 0.7))
    return best


def _unique_faces(faces: np.ndarray) -> np.ndarray:
    """Faces with the same three vertices (in any order) kept once."""
    if len(faces) == 0:
        return faces
    _, first = np.unique(np.sort(faces, axis=1), axis=0, return_index=True)
    return faces[np.sort(first)]


def reduce_faces(vertices: np.ndarray, faces: np.ndarray, max_faces: int
                 ) -> tuple[np.ndarray, np.ndarray]:
    """At most about `max_faces` faces (unchanged when already below), by `cluster`.

    Args:
        vertices: (V, 3) float.
        faces: (F, 3) int.
        max_faces: the budget (> 0).
    """
    if len(faces) <= max_faces:
        return vertices, faces
    return cluster(vertices, faces, max_faces)
