"""Count link-pair collisions over many configurations: a numpy broad phase, then coal.

For a block of samples, robotdesc's own batched forward kinematics places each link's
bounding sphere; only the (sample, pair) entries whose spheres overlap go to Pinocchio/coal,
which place the shapes from the same q vector as the exhaustive check and test the pair's
geometry pairs until one touches. The broad phase is conservative (spheres bound the
shapes), so the counts equal those of checking every pair in every sample.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from robotdesc.kinematics.geometry import CollisionShape
from robotdesc.kinematics.scene import build_scene
from robotdesc.model.tree import JointChain, link_frames
from robotdesc.srdf.reach import MARGIN, Sphere

#: Rows of the broad phase handled at once (bounds its memory: rows x pairs x 3 floats).
BLOCK_ROWS = 64


@dataclass(frozen=True, eq=False)
class CheckSpec:
    """Everything a checking process needs (picklable).

    Attributes:
        urdf: the URDF text for Pinocchio.
        shapes: the collision shapes, placed in their links' frames.
        pairs: the link pairs to check (sorted names).
        convex: check meshes by their convex hulls.
        tree: the kinematic tree for the broad phase.
        spheres: per shape of `shapes`, its bounding sphere in its link's frame (m).
    """

    urdf: str
    shapes: tuple[CollisionShape, ...]
    pairs: tuple[tuple[str, str], ...]
    convex: bool
    tree: JointChain
    spheres: tuple[Sphere, ...]


class PairChecker:
    """Counts, per pair of `spec.pairs`, the samples in which the two links touch."""

    def __init__(self, spec: CheckSpec) -> None:
        self.spec = spec
        scene = build_scene(spec.urdf, spec.shapes, spec.pairs, spec.convex)
        self._pin = scene.pin
        self.model, self.data = scene.model, scene.data
        self.geometry, self.geometry_data = scene.geometry, scene.geometry_data
        #: per geometry pair: the link pair it belongs to, and its two shapes
        self.owner, self.first, self.second = scene.owner, scene.first, scene.second
        index = {name: k for k, name in enumerate(spec.tree.links)}
        self.shape_link = np.array([index[shape.link] for shape in spec.shapes], dtype=np.int64)
        self.centres = np.array([sphere.centre for sphere in spec.spheres], dtype=float)
        self.radii = np.array([sphere.radius for sphere in spec.spheres], dtype=float)

    def count(self, positions: np.ndarray, q: np.ndarray, active: np.ndarray) -> np.ndarray:
        """Collisions per pair of `spec.pairs` over the rows (only `active` pairs counted).

        Args:
            positions: (n, columns) joint positions for the broad phase (rad or m).
            q: (n, nq) the same configurations as Pinocchio q vectors.
            active: indices of the pairs to check.
        """
        counts = np.zeros(len(self.spec.pairs), dtype=np.int64)
        if len(active) == 0 or len(q) == 0:
            return counts
        chosen = np.flatnonzero(np.isin(self.owner, active))
        first, second, owner = self.first[chosen], self.second[chosen], self.owner[chosen]
        reach = self.radii[first] + self.radii[second] + MARGIN
        for start in range(0, len(q), BLOCK_ROWS):
            rotations, translations = link_frames(self.spec.tree,
                                                  positions[start:start + BLOCK_ROWS])
            world = np.einsum("nkij,kj->nki", rotations[:, self.shape_link], self.centres) \
                + translations[:, self.shape_link]
            gap = world[:, first] - world[:, second]
            near = np.einsum("npi,npi->np", gap, gap) <= reach * reach
            for row in np.flatnonzero(near.any(axis=1)):
                hits = self._touching(q[start + row], chosen[near[row]], owner[near[row]])
                counts[hits] += 1
        return counts

    def _touching(self, q: np.ndarray, pairs: np.ndarray, owners: np.ndarray) -> list[int]:
        """The link pairs (of `owners`) whose geometry pairs (`pairs`) touch at `q`."""
        pin = self._pin
        pin.updateGeometryPlacements(self.model, self.data, self.geometry, self.geometry_data, q)
        touching: list[int] = []
        for pair, link_pair in zip(pairs.tolist(), owners.tolist()):
            if (not touching or touching[-1] != link_pair) and \
                    pin.computeCollision(self.geometry, self.geometry_data, pair):
                touching.append(link_pair)
        return touching


_WORKER: PairChecker | None = None


def install(checker: PairChecker | None) -> None:
    """Make `checker` this process's checker (inherited by forked workers)."""
    global _WORKER
    _WORKER = checker


def start_worker(spec: CheckSpec) -> None:
    """Pool initializer: build this process's checker unless one was inherited."""
    if _WORKER is None or _WORKER.spec is not spec:
        install(PairChecker(spec))


def count_chunk(job: tuple[np.ndarray, np.ndarray, np.ndarray]) -> np.ndarray:
    """Pool task: the counts of one chunk (positions, q, active pair indices)."""
    assert _WORKER is not None, "worker not initialised"
    return _WORKER.count(*job)


def worker_checker() -> Any:
    """This process's checker (None before `install`)."""
    return _WORKER
