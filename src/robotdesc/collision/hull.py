"""One convex hull per link (qhull through scipy), wound outward."""

from __future__ import annotations

import numpy as np

from robotdesc.collision.result import MeshPart


class NoVolumeError(ValueError):
    """The points span no volume (fewer than four, or all coplanar)."""


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
    return (np.asarray(points) @ normal.T - offset <= tolerance).all(axis=1)
