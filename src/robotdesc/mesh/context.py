"""Mesh access for the rules: resolve `<mesh>` references, load and summarize them through
the mesh cache, and measure each link's geometry in the link frame.

The lint driver builds one `MeshContext` per linted file, only when a selected rule needs
meshes. Nothing is read until a rule asks; every answer is remembered for the other rules.
Package names go through the same resolver chain as the xacro expansion, and an unknown
package is reported, never looked up elsewhere.

Plain Python: when every mesh summary comes from the cache, nothing here imports numpy
(the link combination is `robotdesc.mesh.properties`); a cache miss loads the file through
`robotdesc.mesh.analyze`, which imports the readers then.
"""

from __future__ import annotations

import logging
import math
import os
from collections.abc import Iterator
from dataclasses import dataclass

from robotdesc.cache_dir import cache_folder
from robotdesc.expansion.packages import package_lookup
from robotdesc.forked import can_fork
from robotdesc.mesh.analyze import analyze_mesh_file, summarize_file
from robotdesc.mesh.cache import MeshCache
from robotdesc.mesh.errors import DEFAULT_LIMITS, MeshError, MeshLimits
from robotdesc.mesh.locate import MeshLocator
from robotdesc.mesh.prefetch import MIN_JOBS, Job, Prefetch
from robotdesc.mesh.primitives import primitive_properties
from robotdesc.mesh.properties import MassProperties, Vec3, combine, moved_bounds
from robotdesc.mesh.records import MassMethod, MeshSummary
from robotdesc.mesh.resolve import MeshResolution, PackageLookup
from robotdesc.mesh.settings import MeshSettings
from robotdesc.model.elements import (
    Box,
    Capsule,
    Collision,
    Cylinder,
    Link,
    MeshRef,
    Robot,
    Sphere,
    Visual,
)

log = logging.getLogger(__name__)

#: One `<mesh>` of the robot: (link, "visual" | "collision", index, element, reference).
MeshUse = tuple[Link, str, int, Visual | Collision, MeshRef]

#: Methods whose mass properties are those of the surface itself (not a hull estimate).
TRUSTED_METHODS = frozenset({MassMethod.EXACT, MassMethod.FLIPPED, MassMethod.HOLES_CAPPED})


@dataclass(frozen=True)
class MeshLookup:
    """One `<mesh>` reference, resolved and (when it resolved) summarized.

    Attributes:
        ref: the reference as written.
        resolution: where it leads, or why it does not.
        summary: mass properties at density 1, bounds and health; None when not available.
        error: why the file could not be read as a mesh, if it could not.
    """

    ref: MeshRef
    resolution: MeshResolution
    summary: MeshSummary | None = None
    error: MeshError | None = None


@dataclass(frozen=True)
class LinkGeometry:
    """The measured geometry of one link, in the link frame.

    Attributes:
        link: the link's name.
        source: "collision" or "visual": which geometry was measured; "" when none.
        properties: combined mass properties at density 1 kg/m^3 (mass = volume, m^3), or
            None when nothing could be measured.
        bounds: axis-aligned bounds (lower, upper corner, m) of the measured geometry.
        unmeasured: why a geometry of the source could not be measured, one entry each.
        estimated: a part's properties are a convex-hull estimate, not the surface's own.
        notes: how the source was chosen, and the fallbacks taken.
    """

    link: str
    source: str
    properties: MassProperties | None
    bounds: tuple[Vec3, Vec3] | None
    unmeasured: tuple[str, ...] = ()
    estimated: bool = False
    notes: tuple[str, ...] = ()

    @property
    def complete(self) -> bool:
        """Every geometry of the source was measured."""
        return self.properties is not None and not self.unmeasured

    @property
    def trusted(self) -> bool:
        """Complete and exact enough to judge a declared inertia against."""
        return (self.properties is not None and not self.unmeasured and not self.estimated
                and self.properties.volume > 0)


class MeshContext:
    """Mesh access for one robot.

    Args:
        robot: the parsed description.
        settings: the config's mesh settings.
        find_package: package name -> root directory (None when unknown).
        cache: the mesh cache, or None to recompute every summary.
        limits: size limits for mesh files.
    """

    def __init__(self, robot: Robot, settings: MeshSettings, find_package: PackageLookup,
                 cache: MeshCache | None = None, limits: MeshLimits = DEFAULT_LIMITS) -> None:
        self.robot = robot
        self.settings = settings
        self._package_lookup = find_package
        self._cache = cache
        self._limits = limits
        self._lookups: dict[tuple[str, str, tuple[float, ...]], MeshLookup] = {}
        self._links: dict[tuple[str, str | None], LinkGeometry] = {}
        #: where each `<mesh>` leads: the one locator, under the config's mesh policy
        self.locator = MeshLocator.with_settings(robot, find_package, settings)
        self._meshes: tuple[MeshUse, ...] | None = None
        self._by_ref: dict[int, tuple[MeshRef, MeshLookup]] = {}  # every rule asks again
        self._ahead: Prefetch | None = None

    def find_package(self, name: str) -> str | None:
        """The root directory of package `name` through the lint's resolver chain (the
        same one the expansion used), or None when the package is unknown."""
        return self._package_lookup(name)

    @classmethod
    def for_file(cls, robot: Robot, target: str, settings: MeshSettings,
                 package_paths: tuple[str, ...] = (),
                 package_map: tuple[tuple[str, str], ...] = (), *, use_cache: bool = True,
                 cache_dir: str | None = None,
                 find_package: PackageLookup | None = None) -> MeshContext:
        """The context for a linted file: the expansion's package chain and the mesh cache
        (off with `use_cache` False, the run's `--no-cache`, or the config's `cache`).

        `find_package`: the run's package lookup when the caller built it (then
        `package_paths` and `package_map` are not read); else one is built here."""
        if find_package is None:
            find_package = package_lookup(target, package_paths, package_map)
        directory = cache_folder(settings.cache and use_cache, cache_dir)
        return cls(robot, settings, find_package, MeshCache(directory) if directory else None)

    # --- one mesh -----------------------------------------------------------------------

    def lookup(self, ref: MeshRef) -> MeshLookup:
        """Resolve and summarize one `<mesh>` (remembered per file, base and scale)."""
        seen = self._by_ref.get(id(ref))
        if seen is not None and seen[0] is ref:
            return seen[1]
        key = (ref.filename, self.locator.base_dir(ref), tuple(ref.scale))
        found = self._lookups.get(key)
        if found is None:
            found = self._lookup(ref)
            self._lookups[key] = found
        self._by_ref[id(ref)] = (ref, found)  # holding `ref` keeps its id unique
        return found

    def _lookup(self, ref: MeshRef) -> MeshLookup:
        resolution = self.locator.locate(ref)
        if not resolution.ok or resolution.path is None:
            return MeshLookup(ref, resolution)
        try:
            summary = _summary(resolution.path, tuple(ref.scale), self._limits, self._cache,
                               self._ahead)
        except MeshError as error:
            return MeshLookup(ref, resolution, error=error)
        return MeshLookup(ref, resolution, summary)

    # --- all meshes ---------------------------------------------------------------------

    def summarize_ahead(self) -> None:
        """Start summarizing, in a forked child process (`robotdesc.mesh.prefetch`), the
        mesh files no summary is known for yet (none in this process, and no mesh cache or
        an empty one), when there are several and this process may fork: the caller does
        other work meanwhile, and `lookup` takes each summary from the child."""
        if self._ahead is not None or not can_fork() or not (
                self._cache is None or self._cache.is_empty()):
            return
        jobs: dict[Job, None] = {}  # in the order the rules will ask, each file once
        for _link, _kind, _index, _shape, ref in self.meshes():
            resolution = self.locator.locate(ref)
            if resolution.ok and resolution.path is not None:
                job = (resolution.path, tuple(ref.scale))
                if job not in jobs and _remembered(job[0], job[1], self._limits,
                                                   self._cache) is None:
                    jobs[job] = None
        if len(jobs) >= MIN_JOBS:
            self._ahead = Prefetch(list(jobs), self._limits, summarize_file)

    def close(self) -> None:
        """End the child `summarize_ahead` started, if any (summaries not taken yet are
        computed here when asked for)."""
        if self._ahead is not None:
            self._ahead.close()
            self._ahead = None

    def meshes(self) -> Iterator[MeshUse]:
        """Every `<mesh>`: (link, "visual" | "collision", index, element, reference)."""
        if self._meshes is None:
            found: list[MeshUse] = []
            for link in self.robot.links:
                for kind, index, shape in link.shapes():
                    if isinstance(shape.geometry, MeshRef):
                        found.append((link, kind, index, shape, shape.geometry))
            self._meshes = tuple(found)
        return iter(self._meshes)

    # --- one link -----------------------------------------------------------------------

    def link_geometry(self, link: Link, source: str | None = None) -> LinkGeometry:
        """The link's geometry measured at density 1, in the link frame.

        Args:
            link: the link.
            source: "collision" or "visual"; default: the configured `inertia_source`.
                When the link has no geometry of that kind the other kind is used (and a
                note says so).
        """
        key = (link.name, source)
        if key not in self._links:
            self._links[key] = self._link_geometry(link, source or self.settings.inertia_source)
        return self._links[key]

    def _link_geometry(self, link: Link, wanted: str) -> LinkGeometry:
        """`_measure`, for a link of primitives only (no file read) once per link object in
        this process: the model's parse shares unchanged links between the variants of a
        description and an editor's saves."""
        if any(isinstance(shape.geometry, MeshRef) for _, _, shape in link.shapes()):
            return self._measure(link, wanted)
        remembered = _PRIMITIVE_LINKS.get((id(link), wanted))
        if remembered is not None and remembered[0] is link:
            return remembered[1]
        measured = self._measure(link, wanted)
        if len(_PRIMITIVE_LINKS) >= _PRIMITIVE_LINK_ENTRIES:
            _PRIMITIVE_LINKS.clear()
        _PRIMITIVE_LINKS[(id(link), wanted)] = (link, measured)  # `link` kept: its id stays its
        return measured

    def _measure(self, link: Link, wanted: str) -> LinkGeometry:
        other = "visual" if wanted == "collision" else "collision"
        shapes = _shapes(link, wanted)
        notes: list[str] = []
        source = wanted
        if not shapes and _shapes(link, other):
            shapes, source = _shapes(link, other), other
            notes.append(f"no {wanted} geometry: measured the {other} geometry")
        if not shapes:
            return LinkGeometry(link.name, "", None, None, notes=("no geometry",))
        measured = tuple((self._shape_properties(shape), shape.origin.xyz, shape.origin.rpy)
                         for shape in shapes)
        # -0.0 equals 0.0 as a key, but the zeros' signs of the result may differ: not kept
        keep = not any(v == 0.0 and math.copysign(1.0, v) < 0.0
                       for shape in shapes for v in (*shape.origin.xyz, *shape.origin.rpy))
        combined = _COMBINED.get(measured) if keep else None
        if combined is None:
            combined = _combine(measured)
            if keep:
                if len(_COMBINED) >= _COMBINED_ENTRIES:
                    _COMBINED.clear()
                _COMBINED[measured] = combined
        properties, bounds, unmeasured, estimated = combined
        if properties is None:
            return LinkGeometry(link.name, source, None, None, unmeasured, notes=tuple(notes))
        if estimated:
            notes.append("part of it is a convex-hull estimate (a mesh is not a closed surface)")
        return LinkGeometry(link.name, source, properties, bounds, unmeasured, estimated,
                            tuple(notes))

    def _shape_properties(self, shape: Visual | Collision
                          ) -> tuple[MassProperties, tuple[Vec3, Vec3], bool] | str:
        """(properties at density 1, local bounds, is a hull estimate), or why not."""
        geometry = shape.geometry
        if geometry is None:
            return "a geometry element is missing or unreadable"
        if isinstance(geometry, MeshRef):
            found = self.lookup(geometry)
            if found.summary is None:
                reason = (found.error.detail if found.error is not None
                          else found.resolution.problem.message if found.resolution.problem
                          else "not available")
                return f"{geometry.filename}: {reason}"
            summary = found.summary
            if summary.properties is None:
                return f"{geometry.filename}: encloses no volume"
            return summary.properties, summary.bounds, summary.method not in TRUSTED_METHODS
        try:
            props = primitive_properties(geometry)
        except ValueError as error:
            return str(error)
        half = _primitive_half_extent(geometry)
        return props, ((-half[0], -half[1], -half[2]), half), False


#: (path, device, inode, size, modification and change times (ns), scale, limits, the mesh
#: cache's folder) -> the summary of that file (or why it is no mesh), for this process.
_SUMMARIES: dict[tuple[object, ...], MeshSummary | MeshError] = {}
_SUMMARY_ENTRIES = 10_000


def _summary(path: str, scale: tuple[float, ...], limits: MeshLimits,
             cache: MeshCache | None, ahead: Prefetch | None = None) -> MeshSummary:
    """`analyze_mesh_file`, remembered in this process under the file's identity (as
    `os.stat` gives it), so that the variants of a description and an editor's saves neither
    hash nor read a mesh file again until it changes; on a miss, the summary `ahead`
    computed is used when it has one.

    Raises:
        MeshError: the file cannot be used as a mesh.
    """
    key = _memo_key(path, scale, limits, cache)
    found = _SUMMARIES.get(key) if key is not None else None
    if found is None:
        computed = ahead.take(path, scale) if ahead is not None else None
        try:
            found = analyze_mesh_file(path, scale, limits, cache, computed)
        except MeshError as error:
            if key is None:
                raise
            found = error
        if key is not None:
            if len(_SUMMARIES) >= _SUMMARY_ENTRIES:
                _SUMMARIES.clear()
            _SUMMARIES[key] = found
    if isinstance(found, MeshError):
        raise found.with_traceback(None)
    return found


def _memo_key(path: str, scale: tuple[float, ...], limits: MeshLimits,
              cache: MeshCache | None) -> tuple[object, ...] | None:
    """The key of a file's summary in this process: its identity and contents' stamp as
    `os.stat` gives them, and the arguments; None when it cannot be stat'ed."""
    try:
        info = os.stat(path)
    except OSError:
        return None
    return (path, info.st_dev, info.st_ino, info.st_size, info.st_mtime_ns, info.st_ctime_ns,
            scale, limits, None if cache is None else str(cache.directory))  # a cache gets it


def _remembered(path: str, scale: tuple[float, ...], limits: MeshLimits,
                cache: MeshCache | None) -> MeshSummary | MeshError | None:
    """The summary of a file this process already has (`_summary`'s memo), or None."""
    key = _memo_key(path, scale, limits, cache)
    return _SUMMARIES.get(key) if key is not None else None


#: One shape as `_measure` combines it: its properties at density 1, local bounds and
#: whether they are a hull estimate (or why it cannot be measured), and its origin.
_Measured = tuple[tuple[MassProperties, tuple[Vec3, Vec3], bool] | str, Vec3, Vec3]
#: A link's shapes combined: (properties, bounds, unmeasured, estimated).
_Combined = tuple[MassProperties | None, tuple[Vec3, Vec3] | None, tuple[str, ...], bool]
#: Combinations already computed in this process, by their shapes' values: the variants of a
#: description and an editor's saves measure the same links again and again.
_COMBINED: dict[tuple[_Measured, ...], _Combined] = {}
_COMBINED_ENTRIES = 100_000


#: (id of a link of primitives only, wanted source) -> (the link, its measured geometry); the
#: link is held so that its id is not reused while the entry lives.
_PRIMITIVE_LINKS: dict[tuple[int, str], tuple[Link, LinkGeometry]] = {}
_PRIMITIVE_LINK_ENTRIES = 50_000


def _combine(measured: tuple[_Measured, ...]) -> _Combined:
    """The shapes' properties moved to the link frame and summed, and their bounds."""
    parts, boxes, unmeasured, estimated = [], [], [], False
    for found, xyz, rpy in measured:
        if isinstance(found, str):
            unmeasured.append(found)
            continue
        props, box, hull = found
        estimated = estimated or hull
        parts.append(props.transformed(xyz, rpy))
        boxes.append(moved_bounds(box, xyz, rpy))
    if not parts:
        return None, None, tuple(unmeasured), False
    low = tuple(min(b[0][i] for b in boxes) for i in range(3))
    high = tuple(max(b[1][i] for b in boxes) for i in range(3))
    return combine(parts), (low, high), tuple(unmeasured), estimated  # type: ignore[return-value]


def _shapes(link: Link, kind: str) -> tuple[Visual | Collision, ...]:
    shapes = link.collisions if kind == "collision" else link.visuals
    return tuple(s for s in shapes if s.geometry is not None or s.where is not None)


def _primitive_half_extent(geometry: Box | Cylinder | Sphere | Capsule) -> Vec3:
    """Half the extent (m) of a primitive's bounds along x, y and z of its own frame."""
    if isinstance(geometry, Box):
        x, y, z = geometry.size
        return (x / 2, y / 2, z / 2)
    r = geometry.radius
    if isinstance(geometry, Sphere):
        return (r, r, r)
    half_length = geometry.length / 2 + (r if isinstance(geometry, Capsule) else 0.0)
    return (r, r, half_length)
