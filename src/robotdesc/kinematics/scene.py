"""A collision scene: the Pinocchio model, one coal object per `<collision>`, and the link
pairs to check. Built in each worker from plain data (`SceneSpec`), so it can cross processes.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np

from robotdesc.kinematics.geometry import CollisionShape


@dataclass(frozen=True, eq=False)
class SceneSpec:
    """Everything needed to build a scene (picklable).

    Attributes:
        urdf: the URDF text for Pinocchio (see urdf_text.py).
        shapes: the collision shapes, placed in their links' frames.
        pairs: the link pairs to check (sorted names).
        convex: check meshes by their convex hulls (faster, more collisions).
    """

    urdf: str
    shapes: tuple[CollisionShape, ...]
    pairs: tuple[tuple[str, str], ...]
    convex: bool = False


class CollisionScene:
    """Checks which link pairs of `spec.pairs` collide at a configuration."""

    def __init__(self, spec: SceneSpec) -> None:
        import pinocchio as pin

        from robotdesc.kinematics.geometry import to_coal

        self.spec = spec
        self.model = pin.buildModelFromXML(spec.urdf, False)
        self.data = self.model.createData()
        self.geometry = pin.GeometryModel()
        by_link: dict[str, list[int]] = {}
        frames = list(self.model.frames)  # one conversion: each `model.frames` access copies
        for shape in spec.shapes:
            frame_id = self.model.getFrameId(shape.link, pin.BODY)
            frame = frames[frame_id]
            placement = frame.placement * pin.SE3(shape.placement[:3, :3].copy(),
                                                  shape.placement[:3, 3].copy())
            obj = pin.GeometryObject(f"{shape.link}/{shape.index}", frame.parentJoint, frame_id,
                                     placement, to_coal(shape, spec.convex))
            by_link.setdefault(shape.link, []).append(self.geometry.addGeometryObject(obj))
        owner = []
        for number, (first, second) in enumerate(spec.pairs):
            for a in by_link.get(first, ()):
                for b in by_link.get(second, ()):
                    self.geometry.addCollisionPair(pin.CollisionPair(a, b))
                    owner.append(number)
        self.owner = np.asarray(owner, dtype=np.int64)
        self.geometry_data = pin.GeometryData(self.geometry)
        self._pin = pin

    def colliding(self, q: np.ndarray) -> np.ndarray:
        """Boolean per pair of `spec.pairs`: do the two links touch at configuration `q`?"""
        pin = self._pin
        pin.computeCollisions(self.model, self.data, self.geometry, self.geometry_data, q, False)
        results = self.geometry_data.collisionResults
        hits = [k for k in range(len(self.owner)) if results[k].isCollision()]
        touching = np.zeros(len(self.spec.pairs), dtype=bool)
        touching[self.owner[hits]] = True
        return touching


def all_link_pairs(links: list[str]) -> list[tuple[str, str]]:
    """Every unordered pair of distinct link names, sorted (combinations of a sorted list
    are already in order: (first, second) with first < second)."""
    return list(combinations(sorted(set(links)), 2))
