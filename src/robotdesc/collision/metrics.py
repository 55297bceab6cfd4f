"""Fidelity of a collision geometry: sampled one-sided distances (exact per point) between
the input surface and the output surface, and the volume ratio. Lengths in metres.

Points are the surface's vertices (at most `samples`, evenly strided) plus `samples`
area-weighted random points with a fixed seed, so a measurement is reproducible. The maxima
are therefore lower bounds of the true Hausdorff distances, tight at the sampling density.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from robotdesc.collision.distance import SurfaceIndex
from robotdesc.collision.result import MeshPart
from robotdesc.mesh.mass import volume_integrals


@dataclass(frozen=True)
class Fidelity:
    """Distances between an input and an output surface (m).

    Attributes:
        forward_mean, forward_max: input points to the output surface.
        backward_mean, backward_max: output points to the input surface.
        diagonal: the input's bounding-box diagonal.
    """

    forward_mean: float
    forward_max: float
    backward_mean: float
    backward_max: float
    diagonal: float

    @property
    def hausdorff_percent(self) -> float:
        """Symmetric Hausdorff distance as % of the diagonal."""
        worst = max(self.forward_max, self.backward_max)
        return 100.0 * worst / self.diagonal if self.diagonal > 0 else 0.0


def sample_surface(vertices: np.ndarray, faces: np.ndarray, samples: int,
                   seed: int = 0) -> np.ndarray:
    """Vertices (strided to at most `samples`) and `samples` area-weighted random points."""
    vertices = np.asarray(vertices, dtype=np.float64)
    corners = vertices[faces]
    area = 0.5 * np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0],
                                         corners[:, 2] - corners[:, 0]), axis=1)
    step = max(1, len(vertices) // samples)
    points = [vertices[::step]]
    if area.sum() > 0:
        rng = np.random.default_rng(seed)
        chosen = rng.choice(len(faces), size=samples, p=area / area.sum())
        u, v = rng.random(samples), rng.random(samples)
        flip = u + v > 1
        u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
        tri = corners[chosen]
        points.append(tri[:, 0] + (tri[:, 1] - tri[:, 0]) * u[:, None]
                      + (tri[:, 2] - tri[:, 0]) * v[:, None])
    return np.concatenate(points)


def merge_parts(parts: list[MeshPart]) -> tuple[np.ndarray, np.ndarray]:
    """Several parts as one (vertices, faces) surface."""
    vertices, faces, offset = [], [], 0
    for part in parts:
        vertices.append(part.vertices)
        faces.append(part.faces + offset)
        offset += len(part.vertices)
    return np.concatenate(vertices), np.concatenate(faces)


def fidelity(source: tuple[np.ndarray, np.ndarray], output: tuple[np.ndarray, np.ndarray],
             samples: int = 2000, seed: int = 0,
             source_index: SurfaceIndex | None = None) -> Fidelity:
    """Distances between the input surface `source` and `output` ((vertices, faces) each).

    `source_index`, the `SurfaceIndex` of `source` when the caller measures several outputs
    of one input (it is built here otherwise)."""
    sv, sf = source
    ov, of = output
    forward = SurfaceIndex(ov, of).distances(sample_surface(sv, sf, samples, seed))
    index = source_index if source_index is not None else SurfaceIndex(sv, sf)
    backward = index.distances(sample_surface(ov, of, samples, seed + 1))
    diagonal = float(np.linalg.norm(sv.max(axis=0) - sv.min(axis=0)))
    return Fidelity(float(forward.mean()), float(forward.max()), float(backward.mean()),
                    float(backward.max()), diagonal)


def mesh_volume(part: MeshPart) -> float:
    """The volume a closed part encloses (m^3; signed, positive when wound outward)."""
    return volume_integrals(part.vertices[part.faces]).volume


def union_volume(parts: list[MeshPart]) -> float:
    """Volume of the union of closed parts (m^3): manifold3d's boolean union when present,
    else the sum (an overestimate where parts overlap)."""
    if len(parts) == 1:
        return mesh_volume(parts[0])
    try:
        import manifold3d
    except ImportError:
        return sum(mesh_volume(p) for p in parts)
    solids = []
    for part in parts:
        solid = manifold3d.Manifold(manifold3d.Mesh(
            vert_properties=np.ascontiguousarray(part.vertices, dtype=np.float32),
            tri_verts=np.ascontiguousarray(part.faces, dtype=np.uint32)))
        if solid.status() != manifold3d.Error.NoError:
            return sum(mesh_volume(p) for p in parts)
        solids.append(solid)
    return float(manifold3d.Manifold.batch_boolean(solids, manifold3d.OpType.Add).volume())
