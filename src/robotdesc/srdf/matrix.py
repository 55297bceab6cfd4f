"""Classify every link pair as MoveIt's Setup Assistant does: Adjacent, Default, Always, Never.

- Adjacent: the links are one rigid body (joined by fixed joints), or a joint connects their
  bodies (or only bodies without collision geometry lie between), as MoveIt's Setup Assistant
  sees them.
- Default: they collide at the default configuration (each joint at 0, or at the middle of
  its range when 0 is outside it, as MoveIt sets it).
- Always: they collide in at least `always_fraction` of the samples.
- Never: they never collide in the N samples (never *in N samples*, not a proof).
Pairs colliding sometimes stay enabled. Samples are checked in parallel processes; the
collision counts are sums, so the result does not depend on the number of workers.
"""

from __future__ import annotations

import enum
import logging
import multiprocessing
import sys
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from robotdesc.kinematics.build import KinematicModel, build_model
from robotdesc.kinematics.configuration import default_configuration
from robotdesc.kinematics.geometry import ShapeProblem, collision_shapes
from robotdesc.kinematics.scene import SceneSpec, all_link_pairs
from robotdesc.kinematics.urdf_text import MeshPath
from robotdesc.model import tree
from robotdesc.model.elements import Robot
from robotdesc.model.tree import joint_chain, poses_at
from robotdesc.srdf import engine
from robotdesc.srdf.engine import CheckSpec
from robotdesc.srdf.reach import reach, shape_spheres
from robotdesc.srdf.sampling import sample_positions

log = logging.getLogger(__name__)

#: MoveIt Setup Assistant's default threshold for "always in collision".
ALWAYS_FRACTION = 0.95
#: Below this many samples the work stays in this process (starting workers costs ~1 s).
PARALLEL_MIN_SAMPLES = 2000
#: Samples per round: the classification is looked at after each.
ROUND_SAMPLES = 500
#: Adaptive sampling never stops before this many samples.
ADAPTIVE_MIN_SAMPLES = 2000


class Reason(str, enum.Enum):
    """Why a pair's collision checking is disabled (the SRDF `reason` attribute)."""

    ADJACENT = "Adjacent"
    DEFAULT = "Default"
    ALWAYS = "Always"
    NEVER = "Never"


@dataclass(frozen=True)
class PairResult:
    """One link pair.

    Attributes:
        link1: the first link (names sorted).
        link2: the second link.
        reason: why checking is disabled; None when the pair stays enabled.
        collisions: in how many samples the pair collided (0 for adjacent pairs: not sampled).
        samples: how many samples were checked for this pair (0 for adjacent pairs).
        at_default: the pair collides at the default configuration.
    """

    link1: str
    link2: str
    reason: Reason | None
    collisions: int = 0
    samples: int = 0
    at_default: bool = False

    @property
    def fraction(self) -> float | None:
        """Fraction of samples in collision (None when not sampled)."""
        return self.collisions / self.samples if self.samples else None


@dataclass(frozen=True)
class CollisionMatrix:
    """The classified pairs of a robot and how they were found.

    Attributes:
        robot: the robot's name.
        pairs: every pair of links with collision geometry, sorted.
        samples: N, the number of random configurations checked.
        seed: the random seed (the same seed gives the same matrix).
        always_fraction: the fraction of samples above which a pair is "Always".
        default_positions: the default configuration, joint name -> position (rad or m).
        links_without_geometry: links with no usable collision geometry (never checked).
        problems: collision elements left out (unresolved or unreadable meshes).
        convex: meshes were checked as their convex hulls.
    """

    robot: str
    pairs: tuple[PairResult, ...]
    samples: int
    seed: int
    always_fraction: float = ALWAYS_FRACTION
    default_positions: tuple[tuple[str, float], ...] = ()
    links_without_geometry: tuple[str, ...] = ()
    problems: tuple[ShapeProblem, ...] = ()
    convex: bool = False

    def disabled(self) -> list[PairResult]:
        """The pairs written to the SRDF as `<disable_collisions>`."""
        return [pair for pair in self.pairs if pair.reason is not None]


@dataclass(frozen=True, eq=False)
class PreparedScene:
    """The pieces shared by the matrix and the default-pose rule.

    Attributes:
        geometries: the coal geometry of each shape of `spec` (by its index), built when a
            first configuration needs it and kept for the next ones (a configuration moves
            the shapes, it does not change them: building a mesh's BVH is most of a check).
    """

    kinematics: KinematicModel
    spec: SceneSpec
    adjacent: frozenset[tuple[str, str]]
    links_without_geometry: tuple[str, ...]
    problems: tuple[ShapeProblem, ...]
    geometries: dict[int, Any] = field(default_factory=dict, repr=False)


def prepare_scene(robot: Robot, mesh_path: MeshPath, convex: bool = False) -> PreparedScene:
    """Build the Pinocchio model and the non-adjacent pairs of links with geometry.

    Raises:
        KinematicsUnavailable: Pinocchio is not installed.
        KinematicBuildError: Pinocchio refused the model.
    """
    kinematics = build_model(robot, mesh_path)
    shapes, problems = collision_shapes(robot, mesh_path)
    solid = sorted({shape.link for shape in shapes})
    adjacent = frozenset(tree.adjacent_pairs(robot, solid, collapse_fixed=True))
    pairs = tuple(p for p in all_link_pairs(solid) if p not in adjacent)
    empty = tuple(link.name for link in robot.links if link.name not in set(solid))
    return PreparedScene(kinematics, SceneSpec(kinematics.urdf, tuple(shapes), pairs, convex),
                         adjacent, empty, tuple(problems))


def default_collisions(prepared: PreparedScene) -> list[tuple[str, str]]:
    """Non-adjacent link pairs that collide at the default configuration.

    A broad phase first prunes the pairs whose bounding spheres are apart; coal then checks
    the shapes of the remaining pairs. Link placements come from robotdesc's own forward
    kinematics: a Pinocchio `Data` for a robot with hundreds of joints takes seconds to
    allocate, and one configuration does not need it.
    """
    robot = prepared.kinematics.robot
    return collisions_at(prepared, default_configuration(robot))


def always_in_contact(prepared: PreparedScene, pairs: list[tuple[str, str]],
                      samples: int = 24, seed: int = 0) -> list[tuple[str, str]]:
    """The pairs of `pairs` that collide in every one of `samples` random configurations
    (within the limits, mimic joints following their drivers): links in contact by design,
    such as the bars of a four-bar gripper linkage."""
    if not pairs:
        return []
    robot = prepared.kinematics.robot
    names, positions = sample_positions(robot, samples, seed)
    remaining = list(pairs)
    for row in positions:
        if not remaining:
            break
        configuration = dict(zip(names, (float(v) for v in row)))
        remaining = collisions_at(prepared, configuration, remaining)
    return remaining


def collisions_at(prepared: PreparedScene, configuration: dict[str, float],
                  pairs: list[tuple[str, str]] | None = None) -> list[tuple[str, str]]:
    """The link pairs (default: every non-adjacent pair) that collide at `configuration`
    (joint name -> rad or m; mimic joints resolved, missing joints at 0)."""
    import coal

    from robotdesc.kinematics.geometry import to_coal

    spec = prepared.spec
    robot = prepared.kinematics.robot
    poses = poses_at(robot, configuration)
    world = [poses[shape.link] @ shape.placement for shape in spec.shapes]
    if pairs is not None:
        spec = SceneSpec(spec.urdf, spec.shapes, tuple(pairs), spec.convex)
    near = _near_pairs(spec, world)
    by_link: dict[str, list[int]] = {}
    for number, shape in enumerate(spec.shapes):
        by_link.setdefault(shape.link, []).append(number)
    objects: dict[int, tuple[Any, Any]] = {}

    def placed(number: int) -> tuple[Any, Any]:
        if number not in objects:
            matrix = world[number]
            transform = coal.Transform3s(np.ascontiguousarray(matrix[:3, :3]),
                                         np.ascontiguousarray(matrix[:3, 3]))
            if number not in prepared.geometries:  # the same shapes in every configuration
                prepared.geometries[number] = to_coal(spec.shapes[number], spec.convex)
            objects[number] = (prepared.geometries[number], transform)
        return objects[number]

    request = coal.CollisionRequest()
    colliding = []
    for first, second in near:
        if any(_touch(placed(a), placed(b), request)
               for a in by_link[first] for b in by_link[second]):
            colliding.append((first, second))
    return colliding


def _touch(a: tuple[Any, Any], b: tuple[Any, Any], request: Any) -> bool:
    import coal

    result = coal.CollisionResult()
    coal.collide(a[0], a[1], b[0], b[1], request, result)
    touching: bool = result.isCollision()
    return touching


def _near_pairs(spec: SceneSpec, world: list[np.ndarray]) -> tuple[tuple[str, str], ...]:
    """The pairs of `spec.pairs` whose links' bounding spheres overlap, given each shape's
    world transform (4x4, in the order of `spec.shapes`)."""
    spheres: dict[str, list[tuple[np.ndarray, float]]] = {}
    for shape, matrix in zip(spec.shapes, world):
        points = shape.local_points()
        low, high = points.min(axis=0), points.max(axis=0)
        centre = (low + high) / 2.0
        radius = float(np.linalg.norm(points - centre, axis=1).max())
        spheres.setdefault(shape.link, []).append((matrix[:3, :3] @ centre + matrix[:3, 3], radius))
    if not spec.pairs:
        return ()
    names = sorted(spheres)
    index = {name: k for k, name in enumerate(names)}
    centres = np.zeros((len(names), 3))
    radii = np.zeros(len(names))
    for name, parts in spheres.items():
        points = np.array([c for c, _ in parts])
        centre = (points.min(axis=0) + points.max(axis=0)) / 2.0
        centres[index[name]] = centre
        radii[index[name]] = max(float(np.linalg.norm(c - centre)) + r for c, r in parts)
    first = np.array([index[a] for a, _ in spec.pairs])
    second = np.array([index[b] for _, b in spec.pairs])
    gap = np.linalg.norm(centres[first] - centres[second], axis=1) - radii[first] - radii[second]
    return tuple(pair for pair, apart in zip(spec.pairs, gap.tolist()) if apart <= 1e-9)


@dataclass(frozen=True)
class Progress:
    """Where a matrix computation stands (passed to the `progress` callback after each round).

    Attributes:
        samples: configurations checked so far.
        limit: the most that will be checked (N).
        sampled_pairs: pairs still being sampled.
        changed_at: samples checked when the classification last changed.
    """

    samples: int
    limit: int
    sampled_pairs: int
    changed_at: int


def compute_matrix(robot: Robot, mesh_path: MeshPath, *, samples: int = 10000, seed: int = 0,
                   workers: int = 2, always_fraction: float = ALWAYS_FRACTION,
                   convex: bool = False, adaptive: bool = True,
                   progress: Callable[[Progress], None] | None = None) -> CollisionMatrix:
    """The self-collision matrix of `robot`.

    Pairs whose swept bounding spheres never meet are Never without sampling; pairs whose
    geometry keeps its relative placement (only wheels spinning about their axes between
    them) take their state at the default configuration; the rest are sampled in rounds.

    Args:
        robot: the parsed robot.
        mesh_path: resolves `<mesh>` references (e.g. `mesh.locate.MeshLocator.path`).
        samples: N, the most random configurations to check.
        seed: random seed; the same seed gives the same result (whatever `workers` is).
        workers: processes checking samples in parallel (1: in this process).
        always_fraction: pairs colliding in at least this fraction of samples are "Always".
        convex: check meshes as their convex hulls (faster; may disable fewer pairs).
        adaptive: stop before N once the classification has not changed over the later
            half of the samples checked (and at least `ADAPTIVE_MIN_SAMPLES` were).
        progress: called after each round of samples.
    """
    prepared = prepare_scene(robot, mesh_path, convex)
    defaults = set(default_collisions(prepared))
    shapes = prepared.spec.shapes
    swept = reach(robot, shapes)
    meets = {pair: swept.can_meet(*pair) for pair in prepared.spec.pairs}
    rigid = {pair for pair in prepared.spec.pairs if meets[pair] and swept.rigid(*pair)}
    sampled = tuple(pair for pair in prepared.spec.pairs if meets[pair] and pair not in rigid)
    log.info("srdf: %d pairs not adjacent: %d can never meet, %d rigid, %d to sample",
             len(prepared.spec.pairs), sum(not m for m in meets.values()), len(rigid),
             len(sampled))
    names, positions = sample_positions(robot, samples, seed)
    q = prepared.kinematics.configurations(names, positions)
    spec = CheckSpec(prepared.spec.urdf, shapes, sampled, convex, joint_chain(robot, names),
                     shape_spheres(shapes))
    fixed = np.array([pair in defaults for pair in sampled], dtype=bool)
    counts, checked, drawn = _sample_rounds(spec, positions, q, workers, always_fraction, fixed,
                                            adaptive, progress)
    found = {pair: (int(c), int(n)) for pair, c, n in zip(sampled, counts, checked)}
    results = [PairResult(a, b, Reason.ADJACENT) for a, b in sorted(prepared.adjacent)]
    for pair in prepared.spec.pairs:
        at_default = pair in defaults
        if pair in found:
            count, seen = found[pair]
        else:
            count, seen = (drawn if at_default and pair in rigid else 0), drawn
        results.append(PairResult(pair[0], pair[1], _reason(count, seen, at_default, drawn,
                                                            always_fraction),
                                  count, seen, at_default))
    results.sort(key=lambda r: (r.link1, r.link2))
    default_positions = tuple(sorted(default_configuration(robot).items()))
    return CollisionMatrix(robot.name, tuple(results), drawn, seed, always_fraction,
                           default_positions, prepared.links_without_geometry,
                           prepared.problems, convex)


def _reason(count: int, seen: int, at_default: bool, drawn: int,
            always_fraction: float) -> Reason | None:
    """A pair's class from its collisions in `seen` samples (of `drawn`)."""
    if at_default:
        return Reason.DEFAULT
    if drawn and seen and count >= always_fraction * seen:
        return Reason.ALWAYS
    if count == 0:
        return Reason.NEVER
    return None


def _sample_rounds(spec: CheckSpec, positions: np.ndarray, q: np.ndarray, workers: int,
                   always_fraction: float, at_default: np.ndarray, adaptive: bool,
                   progress: Callable[[Progress], None] | None
                   ) -> tuple[np.ndarray, np.ndarray, int]:
    """Check the samples round by round; a pair leaves the rounds once more samples cannot
    change its class (Default after the first round; colliding sometimes, with more misses
    than an Always pair may have among all N).

    Returns:
        Per pair of `spec.pairs`: collisions and samples checked; and the samples drawn.
    """
    limit = len(q)
    counts = np.zeros(len(spec.pairs), dtype=np.int64)
    checked = np.zeros(len(spec.pairs), dtype=np.int64)
    active = np.arange(len(spec.pairs))
    if not len(active) or not limit:
        return counts, checked, limit
    allowed_misses = (1.0 - always_fraction) * limit
    classes = np.zeros(len(spec.pairs), dtype=np.int8)
    done, changed_at = 0, 0
    with _Checkers(spec, workers if limit >= PARALLEL_MIN_SAMPLES else 1) as checkers:
        while done < limit and len(active):
            end = min(limit, done + ROUND_SAMPLES)
            counts += checkers.count(positions[done:end], q[done:end], active)
            checked[active] += end - done
            done = end
            now = _classes(counts, checked, always_fraction)
            if np.any(now != classes):
                changed_at = done
            classes = now
            misses = checked - counts
            keep = ~at_default[active] & ~((counts[active] > 0)
                                           & (misses[active] > allowed_misses))
            active = active[keep]
            if progress is not None:
                progress(Progress(done, limit, len(active), changed_at))
            if adaptive and done >= ADAPTIVE_MIN_SAMPLES and done - changed_at >= done / 2:
                log.info("srdf: no pair changed class over the last %d of %d samples; stopping",
                         done - changed_at, done)
                break
    return counts, checked, done


def _classes(counts: np.ndarray, checked: np.ndarray, always_fraction: float) -> np.ndarray:
    """0 never collided, 1 sometimes, 2 always (per pair)."""
    always = (checked > 0) & (counts >= always_fraction * checked)
    return np.where(counts == 0, 0, np.where(always, 2, 1)).astype(np.int8)


class _Checkers:
    """The checker of this process, or a pool of worker processes sharing one round."""

    def __init__(self, spec: CheckSpec, workers: int) -> None:
        self.spec, self.workers = spec, workers
        self.pool: ProcessPoolExecutor | None = None

    def __enter__(self) -> "_Checkers":
        method = _start_method()
        if self.workers <= 1 or method == "fork":
            engine.install(engine.PairChecker(self.spec))  # built once, inherited by forks
        if self.workers > 1:
            self.pool = ProcessPoolExecutor(self.workers,
                                            mp_context=multiprocessing.get_context(method),
                                            initializer=engine.start_worker,
                                            initargs=(self.spec,))
        return self

    def __exit__(self, *exc: object) -> None:
        if self.pool is not None:
            self.pool.shutdown(cancel_futures=True)
        engine.install(None)

    def count(self, positions: np.ndarray, q: np.ndarray, active: np.ndarray) -> np.ndarray:
        """Collisions per pair over the rows, split among the workers."""
        if self.pool is None:
            return engine.count_chunk((positions, q, active))
        parts = np.array_split(np.arange(len(q)), self.workers)
        jobs = [(positions[part], q[part], active) for part in parts if len(part)]
        return sum(self.pool.map(engine.count_chunk, jobs),
                   np.zeros(len(self.spec.pairs), dtype=np.int64))


def _start_method() -> str:
    """fork on Linux (no re-import, and no `if __name__ == "__main__"` needed in a caller's
    script); spawn elsewhere (fork is unsafe on macOS)."""

    return "fork" if sys.platform.startswith("linux") else "spawn"
