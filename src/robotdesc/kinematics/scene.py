"""A collision scene: the Pinocchio model, one coal object per `<collision>`, and the link
pairs to check. Built in each worker from plain data (`SceneSpec`), so it can cross processes.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from itertools import combinations
from typing import Any

import numpy as np

from robotdesc.kinematics.geometry import CollisionShape, to_coal


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


@dataclass(frozen=True, eq=False)
class PinocchioScene:
    """The one Pinocchio scene builder's result (kinematics' CollisionScene and srdf's
    PairChecker both build theirs with `build_scene`).

    Attributes:
        pin: the pinocchio module.
        model, data, geometry, geometry_data: Pinocchio's model and geometry, with one
            geometry object per shape and one collision pair per pair of their shapes.
        owner: per geometry pair, the index of the link pair (of `pairs`) it belongs to.
        first, second: per geometry pair, its two geometry objects.
    """

    pin: Any
    model: Any
    data: Any
    geometry: Any
    geometry_data: Any
    owner: np.ndarray
    first: np.ndarray
    second: np.ndarray


def build_scene(urdf: str, shapes: Sequence[CollisionShape],
                pairs: Sequence[tuple[str, str]], convex: bool = False) -> PinocchioScene:
    """The Pinocchio model of `urdf` with a coal object per shape (placed in its link's
    frame, m) and a collision pair per two shapes of a link pair of `pairs`."""
    import pinocchio as pin

    model = pin.buildModelFromXML(urdf, False)
    geometry = pin.GeometryModel()
    by_link: dict[str, list[int]] = {}
    frames = list(model.frames)  # one conversion: each `model.frames` access copies
    for shape in shapes:
        frame_id = model.getFrameId(shape.link, pin.BODY)
        frame = frames[frame_id]
        placement = frame.placement * pin.SE3(shape.placement[:3, :3].copy(),
                                              shape.placement[:3, 3].copy())
        obj = pin.GeometryObject(f"{shape.link}/{shape.index}", frame.parentJoint, frame_id,
                                 placement, to_coal(shape, convex))
        by_link.setdefault(shape.link, []).append(geometry.addGeometryObject(obj))
    owner, first, second = [], [], []
    for number, (one, two) in enumerate(pairs):
        for a in by_link.get(one, ()):
            for b in by_link.get(two, ()):
                geometry.addCollisionPair(pin.CollisionPair(a, b))
                owner.append(number)
                first.append(a)
                second.append(b)
    return PinocchioScene(pin, model, model.createData(), geometry, pin.GeometryData(geometry),
                          np.asarray(owner, dtype=np.int64), np.asarray(first, dtype=np.int64),
                          np.asarray(second, dtype=np.int64))


class CollisionScene:
    """Checks which link pairs of `spec.pairs` collide at a configuration."""

    def __init__(self, spec: SceneSpec) -> None:
        self.spec = spec
        scene = build_scene(spec.urdf, spec.shapes, spec.pairs, spec.convex)
        self.model, self.data = scene.model, scene.data
        self.geometry, self.geometry_data = scene.geometry, scene.geometry_data
        self.owner = scene.owner
        self._pin = scene.pin

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
