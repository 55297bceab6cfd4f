"""The parameters of one collision generation run (all frozen, all in the cache key)."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import asdict, dataclass, field
from typing import Any

from robotdesc.collision.limits import EngineLimits
from robotdesc.collision.methods import DEFAULT_METHOD, METHOD_TABLE, METHODS_BY_NAME
from robotdesc.errors import CollisionOptionError

#: The method names (the table: `robotdesc.collision.methods`).
METHODS = tuple(m.name for m in METHOD_TABLE)
#: auto: the robot-wide triangle budget by default, sized from the Engineer papers: their
#: hand-made collision had 5,644 polygons for the whole crawler (001, Table II).
DEFAULT_BUDGET = 5000
#: auto: the version of the candidate menu (its ladders); raise it when they change.
AUTO_MENU_VERSION = 2
PRIMITIVE_KINDS = ("box", "cylinder", "sphere", "capsule")
#: The decimation engines (mirrors robotdesc.collision.decimate.ENGINES, kept import-free).
DECIMATORS = ("meshoptimizer", "fast-simplification")


@dataclass(frozen=True)
class CollisionOptions:
    """How to make collision geometry.

    Attributes:
        method: one of METHODS.
        ratio: decimate: share of the input's faces to keep (0 < ratio <= 1).
        faces: decimate: face budget per link (overrides `ratio` when set).
        min_faces: decimate: never aim below this many faces.
        decimator: decimate: the engine tried first, "meshoptimizer" or
            "fast-simplification" (the other is the fallback; see decimate.py).
        adapt: meet the target and the engine limits by default: decimate raises a
            `ratio` budget step by step (doubling, up to the input's faces or the engine's
            faces per mesh) until the target is met; hull and coacd reduce a hull over the
            engine's vertices per hull. Off: results over either are findings only.
        threshold: coacd: concavity threshold (smaller: more, tighter hulls).
        max_hulls: coacd: hull count per link (-1: no limit).
        hull_vertices: coacd: vertices per hull (CoACD simplifies each hull to this).
        coacd_iterations: coacd: Monte Carlo tree search iterations (CoACD's own default
            150; 40 here, see docs/collision.md for the Engineer's timings).
        coacd_depth: coacd: Monte Carlo tree search depth (CoACD's 3; 2 here).
        coacd_nodes: coacd: Monte Carlo tree search nodes per level (CoACD's 20; 10 here).
        preprocess_resolution: coacd: voxel resolution of its manifold pre-processing.
        coacd_input_faces: coacd: a mesh over this many faces is decimated to it before
            CoACD runs (its time grows with the faces; fidelity is measured against the
            original); 0: never.
        seed: coacd: random seed (fixed, so outputs are reproducible).
        primitives: primitive: the kinds tried, among PRIMITIVE_KINDS.
        target_percent: fidelity target: symmetric Hausdorff distance as % of the link's
            bounding-box diagonal (decimate results over it are findings); auto: % of the
            robot's largest link diagonal, one tolerance in metres for every link.
        auto_order: auto: the methods whose results are candidates (coacd only for a link
            that no primitive nor its hull fits within the target).
        budget_triangles: auto: the robot-wide budget of triangles (summed over every
            link, identical links counted each time; primitives count none); 0: none.
        no_contact: auto: link name patterns left out of contact on request (no
            `<collision>`), e.g. a belt that touches the ground only through its wheels.
        samples: surface points sampled per direction for the distances.
        source: "visual" (derive from the visual meshes, default) or "collision".
        mesh_timeout_s: wall-clock limit of one link's worker (s).
        limits: the engine limits checked.
    """

    method: str = DEFAULT_METHOD
    ratio: float = 0.02
    faces: int | None = None
    min_faces: int = 64
    decimator: str = "meshoptimizer"
    adapt: bool = True
    threshold: float = 0.1
    max_hulls: int = 16
    hull_vertices: int = 64
    coacd_iterations: int = 40
    coacd_depth: int = 2
    coacd_nodes: int = 10
    preprocess_resolution: int = 30
    coacd_input_faces: int = 2000
    seed: int = 0
    primitives: tuple[str, ...] = PRIMITIVE_KINDS
    target_percent: float = 1.0
    auto_order: tuple[str, ...] = ("primitive", "hull", "decimate", "coacd")
    budget_triangles: int = DEFAULT_BUDGET
    no_contact: tuple[str, ...] = ()
    samples: int = 2000
    source: str = "visual"
    mesh_timeout_s: float = 300.0
    limits: EngineLimits = field(default_factory=EngineLimits)

    def validated(self) -> CollisionOptions:
        """Self, after checking every value.

        Raises:
            CollisionOptionError: a value out of range or unknown, naming the option (a
                usage error: exit code 2 on the command line).
        """
        problem = next(self._problems(), None)
        if problem is not None:
            raise CollisionOptionError(*problem)
        return self

    def _problems(self) -> Iterator[tuple[str, object, str]]:
        """(option, value, message) of each value out of range, in the order checked."""
        if self.method not in METHODS:
            yield ("method", self.method,
                   f"unknown method '{self.method}' (choose from {', '.join(METHODS)})")
        if not 0 < self.ratio <= 1:
            yield "ratio", self.ratio, f"ratio must be in (0, 1], got {self.ratio}"
        if self.faces is not None and self.faces < 4:
            yield "faces", self.faces, f"faces must be at least 4, got {self.faces}"
        if self.decimator not in DECIMATORS:
            choices = ", ".join(DECIMATORS)
            yield ("decimator", self.decimator,
                   f"unknown decimator '{self.decimator}' (choose from {choices})")
        if not 0 < self.threshold <= 1:
            yield "threshold", self.threshold, f"threshold must be in (0, 1], got {self.threshold}"
        if self.max_hulls == 0 or self.max_hulls < -1:
            yield ("max_hulls", self.max_hulls,
                   f"max hulls must be positive or -1, got {self.max_hulls}")
        for name in ("coacd_iterations", "coacd_depth", "coacd_nodes", "preprocess_resolution"):
            if getattr(self, name) < 1:
                yield (name, getattr(self, name),
                       "coacd iterations, depth, nodes and resolution must be positive")
        if self.coacd_input_faces < 0 or 0 < self.coacd_input_faces < 4:
            yield ("coacd_input_faces", self.coacd_input_faces,
                   f"coacd input faces must be 0 or at least 4, got {self.coacd_input_faces}")
        if self.hull_vertices < 4:
            yield ("hull_vertices", self.hull_vertices,
                   f"hull vertices must be at least 4, got {self.hull_vertices}")
        unknown = [k for k in self.primitives if k not in PRIMITIVE_KINDS]
        if unknown or not self.primitives:
            yield ("primitives", self.primitives,
                   f"primitives must be among {', '.join(PRIMITIVE_KINDS)}")
        bad = [m for m in self.auto_order if m not in METHODS or m == "auto"]
        if bad or not self.auto_order:
            given = ", ".join(self.auto_order)
            methods = "decimate, hull, coacd, primitive"
            yield ("auto_order", self.auto_order,
                   f"auto order must list methods among {methods}; got {given}")
        if self.budget_triangles < 0:
            yield ("budget_triangles", self.budget_triangles,
                   f"the triangle budget must be 0 (none) or positive, got {self.budget_triangles}")
        for name, low in (("target_percent", 0.0), ("samples", 9), ("mesh_timeout_s", 0.0)):
            if not getattr(self, name) > low:
                yield name, getattr(self, name), "target, samples and timeout must be positive"
        if self.source not in ("visual", "collision"):
            yield "source", self.source, f"source must be visual or collision, got {self.source}"
        limits = self.limits
        if limits.max_hulls < 1:
            yield ("limits.max_hulls", limits.max_hulls,
                   f"the limit of hulls per link must be at least 1, got {limits.max_hulls}")
        if limits.max_hull_vertices < 4:
            yield ("limits.max_hull_vertices", limits.max_hull_vertices,
                   "the limit of vertices per hull must be at least 4 (a hull needs 4), "
                   + f"got {limits.max_hull_vertices}")
        if limits.max_mesh_faces < 4:
            yield ("limits.max_mesh_faces", limits.max_mesh_faces,
                   f"the limit of faces per mesh must be at least 4, got {limits.max_mesh_faces}")

    def key_fields(self) -> dict[str, Any]:
        """The parameters that change the generated geometry or its report (the cache and
        manifest key): the common ones and those of the method (all of them for auto), so
        that, say, a new decimation ratio leaves CoACD outputs current."""
        data = asdict(self)
        data.pop("limits")
        data["mesh_face_limit"] = self.limits.max_mesh_faces
        data["hull_vertex_limit"] = self.limits.max_hull_vertices
        data["primitives"] = list(self.primitives)
        data["auto_order"] = list(self.auto_order)
        data["no_contact"] = sorted(self.no_contact)
        relevant = set(METHODS_BY_NAME[self.method].fields)
        if self.method == "auto":  # the menu's ladders are code: a new one, a new key
            data["auto_menu"] = AUTO_MENU_VERSION
            relevant.add("auto_menu")
        if not self.adapt or (self.method == "decimate" and self.faces is not None):
            relevant -= {"adapt", *_ADAPT_FIELDS}  # nothing adapts: the key of before
        return {name: value for name, value in data.items()
                if name in _COMMON_FIELDS or name in relevant}


#: Fields every method's result depends on (seed: CoACD and the fidelity sampling).
_COMMON_FIELDS = ("method", "seed", "target_percent", "samples", "source")
#: The engine limits `adapt` fits results to (in a key only when something adapts).
_ADAPT_FIELDS = ("mesh_face_limit", "hull_vertex_limit")
