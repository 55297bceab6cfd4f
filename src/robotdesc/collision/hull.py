"""One convex hull per link (qhull through scipy), wound outward, and its reduction to an
engine's vertex limit."""

from __future__ import annotations

import numpy as np

from robotdesc.collision.decimate import decimate
from robotdesc.collision.result import MeshPart
from robotdesc.errors import CollisionOptionError, NoVolumeError


def convex_hull(vertices: np.ndarray) -> MeshPart:
    """The convex hull of points as a compact, outward-wound triangle mesh (m).

    Raises:
        NoVolumeError: the points are coplanar, collinear or too few.
    """
    from scipy.spatial import ConvexHull, QhullError

    points = np.unique(np.asarray(vertices, dtype=np.float64), axis=0)
    if len(points) < 4:
        raise NoVolumeError(f"{len(points)} distinct points span no volume")
    try:
        hull = ConvexHull(points)
    except (QhullError, ValueError) as error:
        raise NoVolumeError(f"the points span no volume (qhull: "
                            f"{str(error).splitlines()[0]})") from None
    if not hull.volume > 0:
        raise NoVolumeError("the points span no volume")
    used = np.unique(hull.simplices)
    remap = np.full(len(points), -1, dtype=np.int64)
    remap[used] = np.arange(len(used))
    faces = remap[hull.simplices]
    hull_vertices = points[used]
    corners = hull_vertices[faces]
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    inward = np.einsum("ij,ij->i", normal, hull.equations[:, :3]) < 0
    faces[inward] = faces[inward][:, ::-1]
    return MeshPart(hull_vertices, faces, convex=True)


def contains(part: MeshPart, points: np.ndarray, tolerance: float = 0.0) -> np.ndarray:
    """Which points lie inside a convex part (within `tolerance` metres of its faces)."""
    corners = part.vertices[part.faces]
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    length = np.linalg.norm(normal, axis=1)
    keep = length > 0
    normal = normal[keep] / length[keep, None]
    offset = np.einsum("ij,ij->i", normal, corners[keep, 0])
    inside: np.ndarray = (np.asarray(points) @ normal.T - offset <= tolerance).all(axis=1)
    return inside


def reduce_hull(hull: MeshPart, max_vertices: int) -> MeshPart:
    """A convex hull with at most `max_vertices` vertices, inside `hull` (m).

    The hull's surface is simplified by quadric decimation (meshoptimizer, which keeps a
    subset of the vertices, the corners that matter most) to the faces a convex polytope
    of `max_vertices` vertices has (2V - 4), and re-hulled; the budget shrinks by a tenth
    per round until the vertex count fits. The result's fidelity is for the caller to
    measure. Returns `hull` itself when it already fits.
    """
    if max_vertices < 4:
        raise CollisionOptionError("max_hull_vertices", max_vertices, f"a hull needs at least "
                                   f"4 vertices, the limit is {max_vertices}")
    part = hull
    budget = 2 * max_vertices - 4
    for _ in range(40):
        if len(part.vertices) <= max_vertices:
            return part
        simplified = decimate(part.vertices, part.faces, budget).part
        part = convex_hull(simplified.vertices)
        budget = max(4, int(budget * 0.9))
    return _farthest_points_hull(part, max_vertices)


def _farthest_points_hull(hull: MeshPart, max_vertices: int) -> MeshPart:
    """The hull of `max_vertices` of `hull`'s vertices chosen by farthest-point sampling
    (the fallback when decimation does not shrink the hull)."""
    points = hull.vertices
    chosen = [int(np.argmax(np.linalg.norm(points - points.mean(axis=0), axis=1)))]
    distance = np.linalg.norm(points - points[chosen[0]], axis=1)
    while len(chosen) < max_vertices:
        chosen.append(int(np.argmax(distance)))
        distance = np.minimum(distance, np.linalg.norm(points - points[chosen[-1]], axis=1))
    return convex_hull(points[chosen])
