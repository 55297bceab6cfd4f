"""Quadric decimation to a face budget, checked, with the other engine as the fallback.

Two quadric edge-collapse engines are available:

- "meshoptimizer" (the default): collapses in order of quadric error, never changes the
  topology, and keeps a subset of the input's vertices (no precision lost).
- "fast-simplification" (through trimesh): a threshold sweep. It was seen to stop far
  above the budget (a UR5 upper arm: 29,436 faces asked to 588 stopped at 7,602: its
  collapse test refuses edges next to slivers), to open closed meshes, and, at 2 % of the
  faces, to leave Hausdorff distances 3 to 30 times those of meshoptimizer on
  example-robot-data meshes (a1 thigh 23 % against 2.2 % of the diagonal; iris 35 %
  against 11 %).

Every result is checked (budget reached, closed when the input was): when the chosen
engine fails a check, the other runs and the better result is kept. Which engine ran, and
why, is returned, never hidden.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np

from robotdesc.collision.options import DECIMATORS
from robotdesc.collision.result import MeshPart
from robotdesc.errors import CollisionOptionError
from robotdesc.mesh.health import mesh_health

log = logging.getLogger(__name__)

#: A result may exceed the face budget by this share (collapses come in pairs) plus 4 faces.
BUDGET_SLACK = 0.05
#: The decimation engines, the default first.
ENGINES = DECIMATORS


@dataclass(frozen=True)
class Decimated:
    """A decimation result.

    Attributes:
        part: the mesh.
        engine: the engine whose result this is (one of ENGINES), or "none" (the input was
            already within the budget).
        notes: what was checked and why a fallback ran, in a user's words.
        problems: checks still failing (target missed, opened); empty when all passed.
    """

    part: MeshPart
    engine: str
    notes: tuple[str, ...] = ()
    problems: tuple[str, ...] = ()


def face_budget(faces: int, ratio: float, budget: int | None, min_faces: int) -> int:
    """Faces to aim for: `budget` when given, else `ratio` of `faces`, at least `min_faces`."""
    aim = budget if budget is not None else int(np.ceil(ratio * faces))
    return max(aim, min(min_faces, faces), 4)


def is_closed(vertices: np.ndarray, faces: np.ndarray) -> bool:
    """Watertight: no edge used by one face only (edges where separate sheets touch, which
    a decimator may leave, are allowed)."""
    return mesh_health(vertices[faces]).boundary_edges == 0


def decimate(vertices: np.ndarray, faces: np.ndarray, target: int,
             engine: str = ENGINES[0]) -> Decimated:
    """Reduce a mesh to about `target` faces, keeping it closed when it was.

    Args:
        vertices: (V, 3) merged vertices (m).
        faces: (F, 3) indices.
        target: the face budget.
        engine: the engine tried first (one of ENGINES); the other is the fallback.

    Raises:
        CollisionOptionError: `engine` is not one of ENGINES.
    """
    if engine not in ENGINES:
        raise CollisionOptionError("decimator", engine, f"unknown decimation engine {engine!r} "
                                   f"(choose from {', '.join(ENGINES)})")
    if len(faces) <= target:
        return Decimated(MeshPart(vertices, faces), "none",
                         (f"{len(faces)} faces are already within the budget of {target}",))
    closed = is_closed(vertices, faces)
    first = _RUN[engine](vertices, faces, target)
    problems = _problems(first, target, closed)
    if not problems:
        return Decimated(first, engine)
    notes = (f"{engine} {' and '.join(problems)}",)
    other = ENGINES[1] if engine == ENGINES[0] else ENGINES[0]
    second = _RUN[other](vertices, faces, target)
    still = _problems(second, target, closed)
    if _worse(still, second, problems, first):
        return Decimated(first, engine, notes + (
            f"{other} did no better ({len(second.faces)} faces)",), problems)
    return Decimated(second, other, notes + (f"{other} used instead",), still)


def _worse(problems: tuple[str, ...], part: MeshPart, than_problems: tuple[str, ...],
           than: MeshPart) -> bool:
    """Whether a fallback result is worse than the first: an opened or empty result is worse
    than any other; else the one farther over the budget."""
    def rank(found: tuple[str, ...], mesh: MeshPart) -> tuple[int, int]:
        broken = any("opened" in p or "no faces" in p for p in found)
        return int(broken), len(mesh.faces)
    return rank(problems, part) >= rank(than_problems, than)


def _fast_simplification(vertices: np.ndarray, faces: np.ndarray, target: int) -> MeshPart:
    import trimesh

    mesh = trimesh.Trimesh(vertices=vertices, faces=faces, process=False)
    simple = mesh.simplify_quadric_decimation(face_count=int(target))
    return MeshPart(np.asarray(simple.vertices, dtype=np.float64),
                    np.asarray(simple.faces, dtype=np.int64))


def _meshoptimizer(vertices: np.ndarray, faces: np.ndarray, target: int) -> MeshPart:
    """meshoptimizer's simplification to `target` faces, with no error bound (the budget
    rules; fidelity is measured afterwards). Unused vertices are dropped."""
    import meshoptimizer

    indices = np.ascontiguousarray(faces.ravel(), dtype=np.uint32)
    destination = np.zeros_like(indices)
    count = meshoptimizer.simplify(
        destination, indices, np.ascontiguousarray(vertices, dtype=np.float32),
        target_index_count=3 * int(target), target_error=1.0)
    kept = destination[:count].reshape(-1, 3).astype(np.int64)
    used = np.unique(kept)
    renumber = np.full(len(vertices), -1, dtype=np.int64)
    renumber[used] = np.arange(len(used))
    return MeshPart(np.asarray(vertices[used], dtype=np.float64), renumber[kept])


_RUN = {"meshoptimizer": _meshoptimizer, "fast-simplification": _fast_simplification}


def _problems(part: MeshPart, target: int, closed: bool) -> tuple[str, ...]:
    found = []
    if len(part.faces) == 0:
        return ("produced no faces",)
    if len(part.faces) > target * (1 + BUDGET_SLACK) + 4:
        found.append(f"stopped at {len(part.faces)} faces (budget {target})")
    if closed and not is_closed(part.vertices, part.faces):
        found.append("opened the closed input")
    return tuple(found)
