"""Collision geometry made from a robot's meshes: decimation, convex hulls, convex
decomposition (CoACD) and fitted primitives, each measured against its input.

`generate_collision(robot, method=...)` is the entry point (see generate.py and
docs/collision.md). Heavy backends (fast-simplification, coacd, manifold3d) are imported
inside the worker that needs them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from robotdesc.collision.limits import ENGINE_LIMITS, EngineLimits
from robotdesc.collision.options import METHODS, CollisionOptions
from robotdesc.collision.result import (
    CollisionResult,
    Finding,
    LinkOutcome,
    LinkReport,
    MeshPart,
    PrimitivePart,
)

if TYPE_CHECKING:
    from robotdesc.model.elements import Robot

__all__ = ["ENGINE_LIMITS", "METHODS", "CollisionOptions", "CollisionResult", "EngineLimits",
           "Finding", "LinkOutcome", "LinkReport", "MeshPart", "PrimitivePart",
           "generate_collision"]


def generate_collision(robot: Robot, method: str = "decimate",
                       **options: Any) -> CollisionResult:  # noqa: D401 - thin lazy re-export
    """See `robotdesc.collision.generate.generate_collision` (`options` are its keyword
    arguments)."""
    from robotdesc.collision.generate import generate_collision as run

    return run(robot, method, **options)
