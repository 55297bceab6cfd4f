"""Topological health of a triangle soup: closed, consistently wound, degenerate faces.

Vertices are merged by exact coordinate equality (as MeshLab does when it imports an STL),
then every edge is counted: a closed (watertight) surface uses each undirected edge exactly
twice, and a consistently wound one uses each directed edge once, in opposite directions.
When that leaves holes, vertices on their rims closer than `MERGE_FRACTION` of the mesh's
bounding-box diagonal (or a few float32 steps of its coordinates) are merged too and the
edges counted again: an exporter's rounding opens cracks a nanometre wide that no consumer
sees (MeshLab's "merge close vertices", trimesh's `merge_vertices`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from robotdesc.mesh.mass import bounds
from robotdesc.mesh.records import MeshHealth
from robotdesc.mesh.unique import unique, unique_inverse

__all__ = ["MeshHealth", "Topology", "hole_caps", "merge_tolerance", "merge_vertices",
           "mesh_health",
           "topology"]

#: A face whose area is below this fraction of the squared bounding-box diagonal is degenerate.
DEGENERATE_AREA_FRACTION = 1e-14
#: Rim vertices of holes closer than this fraction of the bounding-box diagonal are one vertex.
MERGE_FRACTION = 1e-6
#: ... or closer than this many float32 steps at the mesh's largest coordinate.
MERGE_FLOAT32_STEPS = 4


@dataclass(frozen=True, eq=False)
class Topology:
    """A soup's merged vertices and its edges, computed once for health and repair.

    Attributes:
        vertices: (V, 3) distinct positions.
        faces: (n, 3) indices into `vertices`, one row per input triangle.
        edge_low, edge_high: per distinct undirected edge, its two vertex indices (low < high).
        edge_uses: faces per distinct undirected edge.
        edge_forward: how many of those faces run the edge low -> high.
    """

    vertices: np.ndarray
    faces: np.ndarray
    edge_low: np.ndarray
    edge_high: np.ndarray
    edge_uses: np.ndarray
    edge_forward: np.ndarray

    @property
    def edge_balance(self) -> np.ndarray:
        """Per distinct edge, (uses low -> high) - (uses high -> low)."""
        balance: np.ndarray = 2 * self.edge_forward - self.edge_uses
        return balance


def topology(triangles: np.ndarray) -> Topology:
    """Merge vertices and count each undirected edge's uses in each direction; when the
    surface has holes, merge their rim vertices within the tolerance and count again.
    """
    vertices, faces = merge_vertices(triangles)
    topo = _count_edges(vertices, faces)
    if not np.any(topo.edge_uses == 1):
        return topo
    merged = _merge_close_rims(topo, merge_tolerance(vertices))
    return topo if merged is None else _count_edges(*merged)


def merge_tolerance(vertices: np.ndarray) -> float:
    """Distance (in the mesh's units) within which two rim vertices are one: `MERGE_FRACTION`
    of the bounding-box diagonal, or `MERGE_FLOAT32_STEPS` float32 steps at the largest
    coordinate, whichever is larger."""
    if len(vertices) == 0:
        return 0.0
    diagonal = float(np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0)))
    largest = float(np.abs(vertices).max())
    step = float(np.spacing(np.float32(largest)))
    return max(MERGE_FRACTION * diagonal, MERGE_FLOAT32_STEPS * step)


def _merge_close_rims(topo: Topology, tolerance: float
                      ) -> tuple[np.ndarray, np.ndarray] | None:
    """(vertices, faces) with rim vertices within `tolerance` of each other merged, or None
    when no two are that close."""
    single = topo.edge_uses == 1
    rim = unique(np.concatenate((topo.edge_low[single], topo.edge_high[single])))
    if tolerance <= 0 or len(rim) < 2:
        return None
    pairs = _close_pairs(topo.vertices[rim], tolerance)
    if len(pairs) == 0:
        return None
    labels = _components(pairs[:, 0], pairs[:, 1], len(rim))
    first = np.full(labels.max() + 1, len(rim))
    np.minimum.at(first, labels, np.arange(len(rim)))
    representative = np.arange(len(topo.vertices))
    representative[rim] = rim[first[labels]]
    kept, remap = unique_inverse(representative)
    return topo.vertices[kept], remap[topo.faces]


def _count_edges(vertices: np.ndarray, faces: np.ndarray) -> Topology:
    """Count each undirected edge's uses in each direction (faces with a repeated vertex
    left out).

    Directed edges are sorted once by a key that holds the undirected edge and, in its lowest
    bit, the direction; a plain sort is several times faster than the argsort it replaces.
    """
    repeated = _repeated(faces)
    good = faces[~repeated] if repeated.any() else faces
    heads = good.reshape(-1)
    tails = good[:, [1, 2, 0]].reshape(-1)
    count = np.int64(max(len(vertices), 1))
    low, high = np.minimum(heads, tails), np.maximum(heads, tails)
    keys = np.sort((low * count + high) * 2 + (heads > tails))
    undirected = keys >> 1
    if len(keys):
        start = np.concatenate(([0], np.flatnonzero(undirected[1:] != undirected[:-1]) + 1))
        uses = np.diff(np.concatenate((start, [len(keys)])))
        forward = np.add.reduceat(1 - (keys & 1), start)
        edge = undirected[start]
    else:
        uses = forward = edge = np.zeros(0, dtype=np.int64)
    return Topology(vertices, faces, edge // count, edge % count, uses, forward)


def mesh_health(triangles: np.ndarray, topo: Topology | None = None) -> MeshHealth:
    """Count degenerate faces and boundary, non-manifold, misoriented and unbalanced edges.

    Args:
        triangles: (n, 3, 3) triangle soup (any length unit).
        topo: its topology, if already computed.
    """
    topo = topology(triangles) if topo is None else topo
    degenerate = _repeated(topo.faces) | _tiny_area(triangles)
    uses, balance = topo.edge_uses, topo.edge_balance
    return MeshHealth(
        triangles=len(triangles),
        vertices=len(topo.vertices),
        degenerate_faces=int(np.count_nonzero(degenerate)),
        boundary_edges=int(np.count_nonzero(uses == 1)),
        nonmanifold_edges=int(np.count_nonzero(uses > 2)),
        misoriented_edges=int(np.count_nonzero((uses == 2) & (balance != 0))),
        unbalanced_edges=int(np.count_nonzero(balance != 0)),
        hole_loops=_count_loops(topo),
    )


def hole_caps(topo: Topology) -> np.ndarray:
    """Triangles that close each hole of a consistently wound surface.

    Every boundary edge a -> b (used once) is joined to the centroid c of its loop by a
    triangle (c, b, a), wound to match its neighbour; a planar hole is closed exactly.

    Returns:
        (k, 3, 3) cap triangles (empty when there are no boundary edges).
    """
    a, b = _boundary_edges(topo)
    if len(a) == 0:
        return np.zeros((0, 3, 3))
    labels = _loop_labels(a, b, len(topo.vertices))
    _, loop = unique_inverse(labels[a])
    weights = np.bincount(loop)
    # float: weighted counts (numpy's stubs type every bincount as integer)
    centroid: np.ndarray = np.stack([np.bincount(loop, topo.vertices[a][:, k]) for k in range(3)],
                                    axis=1)
    centroid /= weights[:, None]
    return np.stack([centroid[loop], topo.vertices[b], topo.vertices[a]], axis=1)


def _boundary_edges(topo: Topology) -> tuple[np.ndarray, np.ndarray]:
    """Heads and tails of the edges used by one face, in that face's direction."""
    single = topo.edge_uses == 1
    low, high = topo.edge_low[single], topo.edge_high[single]
    forward = topo.edge_forward[single] == 1
    return np.where(forward, low, high), np.where(forward, high, low)


def merge_vertices(triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Merge exactly equal vertex positions of a soup.

    Rows are grouped by a 64-bit hash of their coordinates, and the grouping is checked
    against the coordinates themselves (an exact sort is used in the unlikely event of a
    hash collision).

    Args:
        triangles: (n, 3, 3) float array.

    Returns:
        (unique vertices (V, 3) float64, faces (n, 3) int64 indices into them).
    """
    flat = triangles.reshape(-1, 3)
    keys = _row_hashes(flat)
    order = np.argsort(keys, kind="stable")
    ordered = keys[order]
    starts = np.empty(len(ordered), dtype=bool)
    starts[:1] = True
    np.not_equal(ordered[1:], ordered[:-1], out=starts[1:])
    inverse = np.empty(len(keys), dtype=np.int64)
    inverse[order] = np.cumsum(starts) - 1
    unique = np.asarray(flat[order[starts]], dtype=np.float64)
    if not np.array_equal(unique[inverse], flat):  # a hash collision: sort exactly instead
        rows = np.asarray(flat, dtype=np.float64) + 0.0  # -0.0 becomes +0.0
        unique, inverse = np.unique(rows, axis=0, return_inverse=True)
    return unique, inverse.reshape(-1, 3).astype(np.int64, copy=False)


def _repeated(faces: np.ndarray) -> np.ndarray:
    repeated: np.ndarray = ((faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2])
                            | (faces[:, 2] == faces[:, 0]))
    return repeated


def _close_pairs(points: np.ndarray, tolerance: float) -> np.ndarray:
    """(i, j) with i < j for every two points within `tolerance` (Euclidean) of each other,
    as an (n, 2) integer array.

    numpy alone, at any size (scipy's k-d tree costs about 0.2 s of imports in a fresh
    process): a grid of cells, or where the grid's cells cannot be numbered in 64 bits, a
    sweep along x. Points with a non-finite coordinate are close to nothing.
    """
    points = np.asarray(points, dtype=np.float64)
    finite = np.isfinite(points).all(axis=1)
    if not finite.all():
        kept = np.flatnonzero(finite)
        found: np.ndarray = kept[_close_pairs(points[finite], tolerance)]
        return found
    limit = tolerance * tolerance
    near = _close_pairs_in_cells(points, tolerance, limit)
    return near if near is not None else _close_pairs_swept(points, tolerance, limit)


#: The most candidate pairs `_close_pairs_swept` holds at once.
_SWEEP_PAIRS = 1 << 20


def _close_pairs_swept(points: np.ndarray, tolerance: float, limit: float) -> np.ndarray:
    """`_close_pairs` by sorting along x: each point is compared with those after it less
    than `tolerance` further along x, a block of points at a time (at most `_SWEEP_PAIRS`
    candidate pairs in memory; every pair when all x are that close)."""
    count = len(points)
    order = np.argsort(points[:, 0], kind="stable")
    xs = points[order, 0]
    later = np.searchsorted(xs, xs + tolerance, side="right") - np.arange(count) - 1
    total = np.concatenate(([0], np.cumsum(later)))
    chunks = []
    start = 0
    while start < count:
        stop = int(np.searchsorted(total, total[start] + _SWEEP_PAIRS, side="right")) - 1
        stop = min(max(stop, start + 1), count)
        counts = later[start:stop]
        rows = np.repeat(np.arange(start, stop), counts)
        cols = rows + 1 + np.arange(int(counts.sum())) - np.repeat(np.cumsum(counts) - counts,
                                                                    counts)
        first, second = order[rows], order[cols]
        close = ((points[first] - points[second]) ** 2).sum(axis=1) <= limit
        first, second = first[close], second[close]
        chunks.append(np.stack((np.minimum(first, second), np.maximum(first, second)), axis=1))
        start = stop
    return np.concatenate(chunks) if chunks else np.zeros((0, 2), dtype=np.int64)


#: The cells `_close_pairs_in_cells` looks into from a point's own cell: itself and the 13
#: neighbours that come after it (the other 13 find the same pairs from the other side).
_LATER_CELLS = tuple((dx, dy, dz) for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)
                     if (dx, dy, dz) >= (0, 0, 0))


def _close_pairs_in_cells(points: np.ndarray, tolerance: float, limit: float
                          ) -> np.ndarray | None:
    """`_close_pairs` by a grid of cells twice `tolerance` wide: only points in the same or
    adjacent cells can be that close, and each candidate pair is tested with the same
    squared distance as the pairwise comparison (so the same pairs are found, as (i, j) with
    i < j, in another order). None when the grid's cell numbers would not fit in 64 bits."""
    if not tolerance > 0 or len(points) < 2 or not np.isfinite(points).all():
        return None
    low = points.min(axis=0)
    cells = np.floor((points - low) / (2.0 * tolerance))
    span = cells.max(axis=0) + 3.0  # one empty cell on each side for the neighbours
    if not np.isfinite(span).all() or float(span.max()) >= 2.0 ** 62 \
            or float(np.prod(span)) >= 2.0 ** 62:
        return None
    cell = cells.astype(np.int64) + 1
    wide = span.astype(np.int64)
    key = (cell[:, 0] * wide[1] + cell[:, 1]) * wide[2] + cell[:, 2]
    order = np.argsort(key, kind="stable")
    ordered = key[order]
    chunks = []
    for dx, dy, dz in _LATER_CELLS:
        wanted = key + (dx * wide[1] + dy) * wide[2] + dz
        first = np.searchsorted(ordered, wanted, side="left")
        counts = np.searchsorted(ordered, wanted, side="right") - first
        total = int(counts.sum())
        if total == 0:
            continue
        rows = np.repeat(np.arange(len(points)), counts)
        offsets = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts)
        cols = order[np.repeat(first, counts) + offsets]
        if (dx, dy, dz) == (0, 0, 0):
            keep = cols > rows
            rows, cols = rows[keep], cols[keep]
        close = ((points[rows] - points[cols]) ** 2).sum(axis=1) <= limit
        rows, cols = rows[close], cols[close]
        chunks.append(np.stack((np.minimum(rows, cols), np.maximum(rows, cols)), axis=1))
    return np.concatenate(chunks) if chunks else np.zeros((0, 2), dtype=np.int64)


def _components(a: np.ndarray, b: np.ndarray, vertex_count: int) -> np.ndarray:
    """Connected-component label per vertex of the undirected graph of edges a - b: the
    lowest vertex index of its component (numpy only: hook roots, then compress paths)."""
    labels = np.arange(vertex_count)
    while True:
        before = labels.copy()
        low = np.minimum(labels[a], labels[b])
        np.minimum.at(labels, labels[a], low)
        np.minimum.at(labels, labels[b], low)
        while True:
            jumped = labels[labels]
            if np.array_equal(jumped, labels):
                break
            labels = jumped
        if np.array_equal(labels, before):
            return labels


def _loop_labels(a: np.ndarray, b: np.ndarray, vertex_count: int) -> np.ndarray:
    """Connected-component label per vertex of the graph of edges a - b."""
    return _components(a, b, vertex_count)


def _count_loops(topo: Topology) -> int:
    a, b = _boundary_edges(topo)
    if len(a) == 0:
        return 0
    labels = _loop_labels(a, b, len(topo.vertices))
    return len(unique(labels[a]))


def _row_hashes(rows: np.ndarray, chunk: int = 1 << 16) -> np.ndarray:
    """A 64-bit hash of each (x, y, z) row's float64 bits (-0.0 and +0.0 hash alike)."""
    out = np.empty(len(rows), dtype=np.uint64)
    m1 = np.uint64(0x9E3779B97F4A7C15)
    m2 = np.uint64(0xC2B2AE3D27D4EB4F)
    m3 = np.uint64(0x165667B19E3779F9)
    shift = np.uint64(29)
    with np.errstate(over="ignore"):
        for start in range(0, len(rows), chunk):
            cols = np.ascontiguousarray(np.asarray(rows[start:start + chunk], dtype=np.float64).T)
            cols += 0.0
            x, y, z = cols.view(np.uint64)
            h = x * m1
            h ^= h >> shift
            h += y * m2
            h ^= h >> shift
            h += z * m3
            h ^= h >> shift
            out[start:start + chunk] = h * m1
    return out


def _tiny_area(triangles: np.ndarray) -> np.ndarray:
    cols = np.asarray(triangles, dtype=np.float64).transpose(2, 1, 0)  # [axis][corner][face]
    (x0, x1, x2), (y0, y1, y2), (z0, z1, z2) = cols
    ax, ay, az = x1 - x0, y1 - y0, z1 - z0
    bx, by, bz = x2 - x0, y2 - y0, z2 - z0
    cx, cy, cz = ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx
    doubled_area_sq = cx * cx + cy * cy + cz * cz
    low, high = bounds(triangles)
    diagonal_sq = float(np.sum((np.asarray(high) - np.asarray(low)) ** 2))
    threshold = 2.0 * DEGENERATE_AREA_FRACTION * diagonal_sq
    tiny: np.ndarray = doubled_area_sq <= threshold * threshold
    return tiny
