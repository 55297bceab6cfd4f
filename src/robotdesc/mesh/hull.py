"""The convex hull of a 3-D point cloud with numpy alone (no qhull: importing scipy.spatial
costs about 0.2 s of CPU in a fresh process, more than the hull of almost any mesh).

Quickhull, inserting many points per round: every hull face with points outside it offers
its farthest point (its eye); the faces each eye sees (its patch: found by a breadth-first
walk done for all eyes at once, or for the few wide ones by testing every face) are replaced
by a cone of triangles from the patch's rim to the eye. Patches must not overlap: of two
eyes that see a common face the farther one goes, the other waits for a later round (so a
round always inserts the farthest eye). Patches that only touch go together, their cones
joined along the common rim edge when it is convex, else the nearer eye waits. Points
outside a replaced face are handed to the face of its cone they are farthest above, or are
inside, as in quickhull. The first hull is that of the extreme points along 24 directions,
which drops most of a mesh's points at once (the usual pre-filter).

Robustness: a point is outside a face only when more than a tolerance (a small multiple of
the points' extent, `RELATIVE_TOLERANCE`) above its plane, so coplanar and duplicate points
never make faces, and a set that is flat or collinear within it has no hull (None). An eye
level with a face next to its patch takes that face too when the new face over their edge
would fold back over it (an eye nearly on the line of a rim edge, common on the float32
flat sides of CAD meshes); a patch must be a disc. Normals come from each triangle's largest
angle. Coplanar hull faces come out as any triangulation of them, wound outward
(counter-clockwise seen from outside), which is all a volume integral needs. Steps that
touch every point go a block at a time (bounded memory for millions of points).

Units: whatever the points are in (metres for meshes); the tolerance scales with them.
"""

from __future__ import annotations

import logging
from collections.abc import Callable

import numpy as np

from robotdesc.mesh.unique import unique

__all__ = ["RELATIVE_TOLERANCE", "convex_hull_faces"]

log = logging.getLogger(__name__)

#: A point is outside a face when above its plane by more than this times the largest
#: coordinate's distance from the points' bounding-box centre: some fifty times the rounding
#: of a height, and small enough that the hull of a slab 1e-8 as thick as wide matches
#: qhull's to 1e-15 (with 1e-12 here it lost up to 2e-6 of its volume).
RELATIVE_TOLERANCE = 1e-14

#: Directions (unit vectors, about evenly spread over a hemisphere: a Fibonacci lattice) along
#: which the extreme points make the first hull, which drops most of a mesh's points at once.
_DIRECTIONS = np.array([
    (np.sqrt(1 - z * z) * np.cos(2.399963229728653 * i),
     np.sqrt(1 - z * z) * np.sin(2.399963229728653 * i), z)
    for i, z in enumerate(np.linspace(1 - 1 / 24, 1 / 24, 24))])

#: Steps of the walk over faces after which the eyes still walking wait for a later round
#: (but the farthest): a round costs a few numpy calls per step for all eyes.
_PATCH_STEPS = 3
#: The most (eye, face) heights `_wide_patches` computes in a round.
_AT_ONCE = 1 << 16

#: Rows per block where a step touches every point (bounded temporaries).
_BLOCK = 1 << 16

#: Each face's edges: edge i runs from vertex i to vertex (i + 1) % 3.
_NEXT = np.array([1, 2, 0])


def convex_hull_faces(points: np.ndarray) -> np.ndarray | None:
    """The triangles of the convex hull of `points`, wound outward.

    Args:
        points: (n, 3) coordinates (any unit; float64 used).

    Returns:
        (m, 3) int64 indices into `points`, each row a triangle whose vertices run
        counter-clockwise seen from outside the hull; None when the points span no volume
        (fewer than four, not finite, or all within the tolerance of a plane or a line).
    """
    coords = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    if len(coords) < 4 or not np.isfinite(coords).all():
        return None
    centre = (coords.min(axis=0) + coords.max(axis=0)) / 2.0
    local = coords - centre  # about the box centre: precise planes far from the origin
    extent = float(np.abs(local).max())
    if not extent > 0:
        return None
    tolerance = extent * RELATIVE_TOLERANCE
    simplex = _tetrahedron(local, tolerance)
    if simplex is None:
        return None
    hull = _Quickhull(local, tolerance, simplex, _extreme_points(local))
    hull.run()  # the hull of the extreme points: most points are inside it
    hull.assign(np.arange(len(local)))
    return hull.run()


def _extreme_points(points: np.ndarray) -> np.ndarray:
    """The indices of the points farthest along each of `_DIRECTIONS`, both ways."""
    found = []
    level = np.zeros(len(_DIRECTIONS))
    for start in range(0, len(points), _BLOCK):  # a block's extremes, then the best of them
        along = _heights(_DIRECTIONS, level, points[start:start + _BLOCK])
        found += [along.argmin(axis=1) + start, along.argmax(axis=1) + start]
    candidates = unique(np.concatenate(found))
    along = _heights(_DIRECTIONS, level, points[candidates])
    return unique(candidates[np.concatenate([along.argmin(axis=1), along.argmax(axis=1)])])


def _heights(normals: np.ndarray, offsets: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Heights (k, n) of points (n, 3) above k planes (unit normals (k, 3), offsets (k,)),
    a row per plane: numpy's matrix product would wake BLAS threads that keep spinning
    after it (measured: 60 % more CPU for a hull), and einsum is ten times slower."""
    columns = np.ascontiguousarray(points.T)
    out: np.ndarray = normals[:, 0:1] * columns[0]
    out += normals[:, 1:2] * columns[1]
    out += normals[:, 2:3] * columns[2]
    out -= offsets[:, None]
    return out


def _farthest(points: np.ndarray, measure: Callable[[np.ndarray], np.ndarray]
              ) -> tuple[int, float]:
    """The index of the point with the largest `measure` (of a block of rows) and that
    value, a block at a time (bounded temporaries for meshes of millions of points)."""
    best, value = 0, -np.inf
    for start in range(0, len(points), _BLOCK):
        values = measure(points[start:start + _BLOCK])
        index = int(values.argmax())
        if values[index] > value:
            best, value = start + index, float(values[index])
    return best, value


def _tetrahedron(points: np.ndarray, tolerance: float) -> np.ndarray | None:
    """Four far-apart points as a tetrahedron's outward-wound faces (4, 3), or None when
    the points are collinear or coplanar within `tolerance`."""
    extremes = np.concatenate([points.argmin(axis=0), points.argmax(axis=0)])
    ends = points[extremes]
    squared = ((ends[:, None, :] - ends[None, :, :]) ** 2).sum(axis=2)
    i, j = np.unravel_index(int(squared.argmax()), squared.shape)
    a, b = int(extremes[i]), int(extremes[j])
    origin = points[a]
    axis = points[b] - origin
    length = float(np.linalg.norm(axis))
    if not length > tolerance:
        return None
    unit = np.tile(axis / length, (min(len(points), _BLOCK), 1))

    def from_line(block: np.ndarray) -> np.ndarray:
        away = _cross(block - origin, unit[:len(block)])
        distance: np.ndarray = np.einsum("ij,ij->i", away, away)
        return distance

    c, squared_distance = _farthest(points, from_line)
    if not np.sqrt(squared_distance) > tolerance:
        return None
    normal = _cross(axis[None, :], (points[c] - origin)[None, :])[0]
    normal /= np.linalg.norm(normal)
    d, _ = _farthest(points, lambda block: np.abs(np.einsum("ij,j->i", block - origin, normal)))
    height = float(np.dot(points[d] - origin, normal))
    if not abs(height) > tolerance:
        return None
    if height > 0:  # d above (a, b, c): wind the base the other way
        b, c = c, b
    return np.array([[a, b, c], [a, d, b], [b, d, c], [c, d, a]], dtype=np.int64)


def _indices(mask: np.ndarray) -> np.ndarray:
    """Where a boolean array is true (np.flatnonzero is a Python function)."""
    found: np.ndarray = mask.nonzero()[0]
    return found


def _filled(size: int, value: int) -> np.ndarray:
    """An int64 array of `size` copies of `value` (np.full is a Python function)."""
    out = np.empty(size, dtype=np.int64)
    out.fill(value)
    return out


def _discs(count: int, owner: np.ndarray, corners: np.ndarray, rim_owner: np.ndarray,
           n_points: int) -> np.ndarray:
    """Whether each of `count` patches is a disc by its Euler characteristic: vertices -
    edges + faces = 1, with edges = (3 faces + horizon edges) / 2.

    Args:
        owner: the patch of each face (f,); corners: the faces' vertex ids (f, 3);
        rim_owner: the patch of each horizon edge; n_points: more than any vertex id.
    """
    faces = np.bincount(owner, minlength=count)
    rim = np.bincount(rim_owner, minlength=count)
    corner_keys = unique(owner.repeat(3) * n_points + corners.ravel())
    vertices = np.bincount(corner_keys // n_points, minlength=count)
    disc: np.ndarray = 2 * vertices - (3 * faces + rim) + 2 * faces == 2
    return disc


def _normals(corners: np.ndarray) -> np.ndarray:
    """Normals (not unit) of triangles (k, 3, 3), each the cross product of the two edges
    at its largest angle (opposite its longest edge): the most precise of the three for a
    sliver, whose other two edges are nearly parallel."""
    edges = corners[:, _NEXT] - corners  # edge i: from corner i to corner i + 1
    longest = np.einsum("kij,kij->ki", edges, edges).argmax(axis=1)
    apex = (longest + 2) % 3  # the corner opposite the longest edge
    rows = np.arange(len(corners))
    after = edges[rows, apex]  # apex -> the next corner
    before = edges[rows, (apex + 2) % 3]  # the previous corner -> apex
    return _cross(after, -before)  # = (next - apex) x (previous - apex)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise cross products of (k, 3) arrays (np.cross costs ~20 Python calls)."""
    ax, ay, az = a[:, 0], a[:, 1], a[:, 2]
    bx, by, bz = b[:, 0], b[:, 1], b[:, 2]
    out = np.empty(a.shape)
    out[:, 0] = ay * bz - az * by
    out[:, 1] = az * bx - ax * bz
    out[:, 2] = ax * by - ay * bx
    return out


class _Quickhull:
    """The growing hull: faces in arrays (vertex indices, the neighbour across each edge,
    unit normal and offset of the plane, alive), and the points still outside it."""

    def __init__(self, points: np.ndarray, tolerance: float, simplex: np.ndarray,
                 candidates: np.ndarray) -> None:
        self.points = points
        self.tolerance = tolerance
        capacity = 64
        self.vertices = np.zeros((capacity, 3), dtype=np.int64)
        self.neighbours = np.zeros((capacity, 3), dtype=np.int64)
        self.normals = np.zeros((capacity, 3))
        self.offsets = np.zeros(capacity)
        self.alive = np.zeros(capacity, dtype=bool)
        self.count = 0
        self.dropped = 0
        self.walk_only = np.zeros(len(points), dtype=bool)  # eyes whose patch must be walked
        self._add(simplex)
        # each face's edge (u, v) is crossed into the face that has (v, u)
        edges = {(int(f[i]), int(f[(i + 1) % 3])): (n, i) for n, f in enumerate(simplex)
                 for i in range(3)}
        for (u, v), (face, i) in edges.items():
            self.neighbours[face, i] = edges[(v, u)][0]
        self.assign(candidates)

    def assign(self, candidates: np.ndarray) -> None:
        """Make `candidates` (point indices) the points outside the hull: each goes to the
        face it is farthest above, or is dropped when above none."""
        faces = _indices(self.alive[:self.count])
        corner = np.zeros(len(self.points), dtype=bool)
        corner[self.vertices[faces]] = True
        candidates = candidates[~corner[candidates]]  # a corner is on the hull, never outside
        step = max(1, _BLOCK * 64 // len(faces))  # at most 4M heights at a time
        outside, owner, height = [], [], []
        for start in range(0, len(candidates), step):
            block = candidates[start:start + step]
            heights = _heights(self.normals[faces], self.offsets[faces], self.points[block])
            best = heights.argmax(axis=0)
            highest = heights[best, np.arange(len(block))]
            above = highest > self.tolerance
            outside.append(block[above])
            owner.append(faces[best[above]])
            height.append(highest[above])
        self.outside = np.concatenate(outside) if outside else candidates[:0]
        self.owner = np.concatenate(owner) if owner else candidates[:0]
        self.height = np.concatenate(height) if height else np.zeros(0)

    def run(self) -> np.ndarray:
        """Insert points until none is outside; the alive faces (m, 3)."""
        while len(self.outside):
            self._round()
        if self.dropped:
            log.debug("convex hull: %d points dropped at a degenerate horizon", self.dropped)
        faces: np.ndarray = self.vertices[:self.count][self.alive[:self.count]]
        return faces

    def _add(self, triangles: np.ndarray) -> np.ndarray:
        """Append faces (k, 3) with their planes; their ids. Neighbours are set by the
        caller."""
        start, stop = self.count, self.count + len(triangles)
        if stop > len(self.alive):
            grow = max(stop, 2 * len(self.alive)) - len(self.alive)
            self.vertices = np.concatenate([self.vertices, np.zeros((grow, 3), np.int64)])
            self.neighbours = np.concatenate([self.neighbours, np.zeros((grow, 3), np.int64)])
            self.normals = np.concatenate([self.normals, np.zeros((grow, 3))])
            self.offsets = np.concatenate([self.offsets, np.zeros(grow)])
            self.alive = np.concatenate([self.alive, np.zeros(grow, dtype=bool)])
        corners = self.points[triangles]
        normal = _normals(corners)
        length = np.sqrt(np.einsum("ij,ij->i", normal, normal))
        usable = length > 0
        normal[usable] /= length[usable, None]
        normal[~usable] = 0.0  # a degenerate sliver: nothing is ever above it
        self.vertices[start:stop] = triangles
        self.normals[start:stop] = normal
        self.offsets[start:stop] = np.einsum("ij,ij->i", normal, corners.mean(axis=1))
        self.alive[start:stop] = True
        self.count = stop
        return np.arange(start, stop)

    def _round(self) -> None:
        """Insert the farthest outside point of every face that has one, except those that
        conflict with a farther one."""
        farthest = np.full(self.count, -np.inf)
        np.maximum.at(farthest, self.owner, self.height)
        lead = self.height == farthest[self.owner]
        eye_of = _filled(self.count, -1)
        eye_of[self.owner[lead]] = self.outside[lead]  # one per face (the last of any tie)
        start_face = _indices(eye_of >= 0)
        eye = eye_of[start_face]
        rank = np.empty(len(eye), dtype=np.int64)
        rank[np.argsort(farthest[start_face], kind="stable")] = np.arange(len(eye))
        accepted, seen_c, seen_f, at_once = self._patches(start_face, eye, rank)
        keep = accepted[seen_c]
        self._replace(eye, rank, accepted, seen_c[keep], seen_f[keep], at_once)

    def _patches(self, start_face: np.ndarray, eye: np.ndarray, rank: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Which eyes may go in this round, the (eye, face) pairs of the faces each sees,
        and which eyes' patches were found at once rather than by a walk.

        Each eye's patch grows from its own face over neighbours while the eye sees them
        (`_sees`), for all eyes at once. Patches must not overlap: a face keeps the rank of
        the farthest eye that saw it, and an eye that meets a face a farther eye (higher
        `rank`) sees stops walking and waits for a later round. (Patches that only touch
        go together when the edge between their cones is convex: `_replace`.) The few eyes
        still walking after `_PATCH_STEPS` steps (wide patches, long strips of faces) take
        every face they are above at once (`_wide_patches`).
        """
        eyes = self.points[eye]
        claim = _filled(self.count, -1)
        claim[start_face] = rank
        waits = np.zeros(len(eye), dtype=bool)
        at_once = np.zeros(len(eye), dtype=bool)
        seen_c = [np.arange(len(eye))]
        seen_f = [start_face]
        front_c, front_f = seen_c[0], start_face
        slot = _filled(self.count, -1)
        steps = 0
        while len(front_c):
            cand_c = front_c.repeat(3)
            cand_f = self.neighbours[front_f].ravel()
            tail = self.vertices[front_f].ravel()
            head = self.vertices[front_f][:, _NEXT].ravel()
            fresh = claim[cand_f] != rank[cand_c]  # not seen by this eye already
            cand_c, cand_f, tail, head = cand_c[fresh], cand_f[fresh], tail[fresh], head[fresh]
            above = self._sees(eyes[cand_c], cand_f, tail, head)
            cand_c, cand_f = cand_c[above], cand_f[above]
            np.maximum.at(claim, cand_f, rank[cand_c])
            mine = claim[cand_f] == rank[cand_c]
            waits[cand_c[~mine]] = True  # a farther eye sees it (now or before)
            index = np.arange(len(cand_f))
            slot[cand_f[mine]] = index[mine]  # one pair per face and eye walks on
            first = mine & (slot[cand_f] == index)
            front_c, front_f = cand_c[first], cand_f[first]
            seen_c.append(front_c)
            seen_f.append(front_f)
            front = ~waits[front_c]
            front_c, front_f = front_c[front], front_f[front]
            steps += 1
            if steps == _PATCH_STEPS and len(front_c):
                wide = unique(front_c)
                wide = wide[~self.walk_only[eye[wide]]]
                if len(wide) and len(wide) * self.count <= _AT_ONCE:
                    at_once[wide] = True
                    front_c, front_f = front_c[~at_once[front_c]], front_f[~at_once[front_c]]
                    keep = [~at_once[part] for part in seen_c]
                    seen_c = [part[k] for part, k in zip(seen_c, keep)]
                    seen_f = [part[k] for part, k in zip(seen_f, keep)]
                    wide_c, wide_f = self._wide_patches(wide, eyes[wide], start_face[wide])
                    seen_c.append(wide_c)
                    seen_f.append(wide_f)
        # each face once per eye: met again in a later step only where a farther eye took
        # it (and then the eye waits), twice in a step only from two faces (one is kept)
        all_c, all_f = np.concatenate(seen_c), np.concatenate(seen_f)
        best_seen = _filled(self.count, -1)
        np.maximum.at(best_seen, all_f, rank[all_c])
        waits[all_c[best_seen[all_f] > rank[all_c]]] = True
        accepted: np.ndarray = ~waits
        return accepted, all_c, all_f, at_once

    def _wide_patches(self, wide: np.ndarray, eyes: np.ndarray, start_face: np.ndarray
                      ) -> tuple[np.ndarray, np.ndarray]:
        """The patches of `wide` eyes (their ids; positions (k, 3); own faces) from every
        alive face at once, as (eye, face) pairs: the faces each is above, with those it is
        level with across an edge of them where the new face would fold back (`_sees`, one
        ring). A patch that is not one disc (rounding on nearly coplanar faces) is caught
        by `_replace`."""
        alive = _indices(self.alive[:self.count])
        heights = _heights(self.normals[alive], self.offsets[alive], eyes)
        inside = np.zeros((len(wide), self.count), dtype=bool)
        column, row = (heights > self.tolerance).nonzero()
        inside[row, alive[column]] = True
        inside[np.arange(len(wide)), start_face] = True
        row, face = inside.nonzero()
        rows = row.repeat(3)
        across = self.neighbours[face].ravel()
        out = ~inside[rows, across]
        rows, across = rows[out], across[out]
        tail = self.vertices[face].ravel()[out]
        head = self.vertices[face][:, _NEXT].ravel()[out]
        folds = self._sees(eyes[rows], across, tail, head)
        inside[rows[folds], across[folds]] = True
        row, face = inside.nonzero()
        return wide[row], face

    def _sees(self, eyes: np.ndarray, faces: np.ndarray, tail: np.ndarray, head: np.ndarray
              ) -> np.ndarray:
        """Whether each eye takes each face into its patch, reached over the face's edge
        (head, tail): when the eye is above the face, or level with it (within the
        tolerance) and the new face (tail, head, eye) would fold back over it (the face's
        third corner above the new face: a sliver from an eye nearly on the edge's line,
        which qhull avoids by merging the two) or have no area (the eye on that line)."""
        height = np.einsum("ij,ij->i", self.normals[faces], eyes) - self.offsets[faces]
        takes: np.ndarray = height > self.tolerance
        # level: within the tolerance, or as far below as an eye on the line of an edge
        # (up to 2 * 3 ** 0.5 times the extent long) can be
        level = _indices(~takes & (height > -4.0 * self.tolerance))
        if len(level):
            tail, head = tail[level], head[level]
            corner = self.vertices[faces[level]].sum(axis=1) - tail - head
            base = self.points[tail]
            cone = _normals(np.stack([base, self.points[head], eyes[level]], axis=1))
            length = np.sqrt(np.einsum("ij,ij->i", cone, cone))
            rise = np.einsum("ij,ij->i", cone, self.points[corner] - base)
            edge = self.points[head] - base
            flat = length <= self.tolerance * np.sqrt(np.einsum("ij,ij->i", edge, edge))
            takes[level] = (rise > self.tolerance * length) | flat
        return takes

    def _replace(self, eye: np.ndarray, rank: np.ndarray, accepted: np.ndarray,
                 seen_c: np.ndarray, seen_f: np.ndarray, at_once: np.ndarray) -> None:
        """Replace each accepted eye's patch by the cone from its horizon to the eye, and
        hand the patch's outside points to the cone's faces.

        Two patches may share horizon edges; the two new faces over such an edge become
        neighbours when the edge between them is convex (neither eye above the other's new
        face), else the nearer eye waits. A patch must be one disc (its horizon one loop
        through distinct vertices, and vertices - edges + faces = 1); rounding on nearly
        coplanar faces can make another shape. Such an eye walks its patch next time if it
        was found at once, else it is dropped (counted in `dropped`)."""
        n_points = len(self.points)
        accepted = accepted.copy()
        broken = np.zeros(len(eye), dtype=bool)
        while True:
            keep = accepted[seen_c]
            seen_c, seen_f = seen_c[keep], seen_f[keep]
            owner = _filled(self.count, -1)
            owner[seen_f] = seen_c
            face = seen_f.repeat(3)
            edge = np.tile(np.arange(3), len(seen_f))
            cone = seen_c.repeat(3)
            across = self.neighbours[face, edge]
            rim = owner[across] != cone
            face, edge, cone, across = face[rim], edge[rim], cone[rim], across[rim]
            other = owner[across]  # -1: the face across stays; else the eye replacing it
            tail = self.vertices[face, edge]
            head = self.vertices[face, _NEXT[edge]]
            shared = _indices(other >= 0)
            if len(shared):
                mine, theirs = cone[shared], other[shared]
                base = self.points[tail[shared]]
                normal = _normals(np.stack([base, self.points[head[shared]],
                                            self.points[eye[mine]]], axis=1))
                length = np.sqrt(np.einsum("ij,ij->i", normal, normal))
                rise = np.einsum("ij,ij->i", normal, self.points[eye[theirs]] - base)
                reflex = rise > self.tolerance * length
                if reflex.any():
                    mine, theirs = mine[reflex], theirs[reflex]
                    accepted[np.where(rank[mine] < rank[theirs], mine, theirs)] = False
                    continue
            key = cone * n_points + tail
            order = np.argsort(key, kind="stable")
            face, cone, across, other, tail, head, key = (
                face[order], cone[order], across[order], other[order], tail[order],
                head[order], key[order])
            next_key = cone * n_points + head
            at = np.minimum(np.searchsorted(key, next_key), len(key) - 1)
            bad = np.zeros(len(eye), dtype=bool)
            bad[cone[key[at] != next_key]] = True
            bad[cone[1:][key[1:] == key[:-1]]] = True  # the horizon meets a vertex twice
            bad |= ~_discs(len(eye), seen_c, self.vertices[seen_f], cone, n_points)
            bad &= accepted
            if bad.any():
                broken |= bad
                accepted &= ~bad
                continue
            break
        self.walk_only[eye[broken & at_once]] = True
        self.dropped += int((broken & ~at_once).sum())
        ids = self._add(np.stack([tail, head, eye[cone]], axis=1))
        self.neighbours[ids, 1] = ids[at]
        self.neighbours[ids[at], 2] = ids
        stays = other < 0
        self.neighbours[ids[stays], 0] = across[stays]
        back = np.argmax(self.neighbours[across[stays]] == face[stays, None], axis=1)
        self.neighbours[across[stays], back] = ids[stays]
        twin = np.searchsorted(key, other[~stays] * n_points + head[~stays])
        self.neighbours[ids[~stays], 0] = ids[twin]  # the other cone's face, reversed
        gone = owner >= 0
        self.alive[:len(gone)][gone] = False
        self._reassign(eye, accepted | (broken & ~at_once), owner, cone, ids)

    def _reassign(self, eye: np.ndarray, done: np.ndarray, owner: np.ndarray,
                  cone: np.ndarray, ids: np.ndarray) -> None:
        """Points outside a replaced face (`owner`: the eye that replaced each face, or -1)
        go to the face of that eye's cone they are farthest above, or are inside now;
        inserted (and dropped) eyes leave the outside set."""
        is_eye = np.zeros(len(self.points), dtype=bool)
        is_eye[eye[done]] = True
        which = owner[self.owner]
        moving = which >= 0
        stays = ~moving & ~is_eye[self.outside]
        moving &= ~is_eye[self.outside]
        points = self.outside[moving]
        which = which[moving]
        first = np.searchsorted(cone, np.arange(len(eye)))
        sizes = np.searchsorted(cone, np.arange(len(eye)), side="right") - first
        counts = sizes[which]
        found = [(self.outside[stays], self.owner[stays], self.height[stays])]
        total = np.concatenate(([0], np.cumsum(counts)))
        begin = 0
        while begin < len(points):  # a block of points, at most 4M (point, face) pairs
            end = max(int(np.searchsorted(total, total[begin] + _BLOCK * 64, side="right")) - 1,
                      begin + 1)
            found.append(self._highest(points[begin:end], first[which[begin:end]],
                                       counts[begin:end], ids))
            begin = end
        self.outside = np.concatenate([part[0] for part in found])
        self.owner = np.concatenate([part[1] for part in found])
        self.height = np.concatenate([part[2] for part in found])

    def _highest(self, points: np.ndarray, first: np.ndarray, counts: np.ndarray,
                 ids: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """For points each with a run of faces (`ids[first:first + count]`), those above
        one of them: (point, the face it is highest above, that height)."""
        pair_point = points.repeat(counts)
        runs = np.cumsum(counts) - counts
        step = np.arange(int(counts.sum())) - runs.repeat(counts)
        pair_face = ids[first.repeat(counts) + step]
        heights = (np.einsum("ij,ij->i", self.normals[pair_face], self.points[pair_point])
                   - self.offsets[pair_face])
        highest = np.maximum.reduceat(heights, runs)  # a point's pairs are consecutive
        top = _indices(heights == highest.repeat(counts))
        best = top[np.searchsorted(top, runs)]  # the first top pair of each point
        best = best[highest > self.tolerance]
        return pair_point[best], pair_face[best], heights[best]
