"""What collision generation returns: new geometry per link and a measured report."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from dataclasses import asdict as as_dict
from typing import TYPE_CHECKING, Any

from robotdesc.model.elements import Box, Capsule, Cylinder, Pose, Robot, Sphere

if TYPE_CHECKING:
    import numpy as np

#: Finding severities: "error" (the link gets no new geometry), "warning" (written, but the
#: run fails: exit 1), "info" (reported only).
SEVERITIES = ("error", "warning", "info")


@dataclass(frozen=True)
class Finding:
    """Something about one link's result a user must know.

    Attributes:
        code: stable kebab-case name ("mesh-error", "worker-crashed", "over-limit", ...).
        severity: one of SEVERITIES.
        message: what happened, with the numbers.
    """

    code: str
    severity: str
    message: str


@dataclass(frozen=True, eq=False)
class MeshPart:
    """One triangle mesh of a link's collision geometry, in the link frame (m).

    Attributes:
        vertices: (V, 3) float64.
        faces: (F, 3) int64, wound counter-clockwise seen from outside.
        convex: the part is a convex hull.
    """

    vertices: np.ndarray
    faces: np.ndarray
    convex: bool = False


@dataclass(frozen=True)
class PrimitivePart:
    """A URDF primitive placed in the link frame."""

    geometry: Box | Cylinder | Sphere | Capsule
    origin: Pose = field(default_factory=Pose)


Part = MeshPart | PrimitivePart


@dataclass(frozen=True)
class LinkReport:
    """The measurements of one link.

    Distances are in metres: `forward` from the input surface to the output, `backward`
    from the output to the input (sampled points, exact distances), and `diagonal` the
    input's bounding-box diagonal that the percentages refer to. `volume_ratio` is output
    over input volume (hulls of a decomposition are united first when manifold3d is present).
    """

    link: str
    method: str
    status: str
    faces_before: int = 0
    vertices_before: int = 0
    faces_after: int = 0
    vertices_after: int = 0
    hulls: int = 0
    volume_ratio: float | None = None
    forward_mean: float | None = None
    forward_max: float | None = None
    backward_mean: float | None = None
    backward_max: float | None = None
    diagonal: float = 0.0
    seconds: float = 0.0
    cached: bool = False
    detail: str = ""
    findings: tuple[Finding, ...] = ()

    @property
    def hausdorff(self) -> float | None:
        """Symmetric Hausdorff distance (m): the larger one-sided maximum."""
        if self.forward_max is None or self.backward_max is None:
            return None
        return max(self.forward_max, self.backward_max)

    def percent(self, value: float | None) -> float | None:
        """A distance as % of the bounding-box diagonal."""
        if value is None or self.diagonal <= 0:
            return None
        return 100.0 * value / self.diagonal

    def to_dict(self) -> dict[str, Any]:
        data = asdict(self)
        data["findings"] = [asdict(f) for f in self.findings]
        data["hausdorff"] = self.hausdorff
        data["hausdorff_percent"] = self.percent(self.hausdorff)
        return data


@dataclass(frozen=True)
class LinkOutcome:
    """One link's new collision geometry (empty when failed or skipped) and its report.

    Attributes:
        key: the hash of the link's sources and the parameters (cache and manifest key).
        alternatives: method auto: every candidate made and measured for the link
            (primitive, hull, decimations at rising budgets, CoACD pieces), from which the
            robot-wide choice (`robotdesc.collision.choose`) picks; empty otherwise.
    """

    report: LinkReport
    parts: tuple[Part, ...] = ()
    key: str = ""
    alternatives: tuple[LinkOutcome, ...] = ()

    @property
    def written(self) -> bool:
        """True when the link gets new geometry (none at all when left out of contact on
        request: method "none")."""
        return (bool(self.parts) or self.report.method == "none") \
            and self.report.status in ("ok", "warning")


@dataclass(frozen=True)
class CollisionResult:
    """The outcome of `generate_collision`: never mutates `robot`.

    Attributes:
        robot: the input robot (unchanged).
        outcomes: one per link with geometry, in document order.
        options: the parameters used (`robotdesc.collision.options.CollisionOptions`).
        seconds: wall time of the whole run (s).
        jobs: worker processes used.
    """

    robot: Robot
    outcomes: tuple[LinkOutcome, ...]
    options: Any
    seconds: float = 0.0
    jobs: int = 1

    def __repr__(self) -> str:
        """A one-line summary (`.outcomes` holds the meshes and per-link reports)."""
        totals = self.totals()
        method = getattr(self.options, "method", "?")
        return (f"<CollisionResult {self.robot.name!r} ({method}): {totals['written']} of "
                f"{totals['links']} links written, {totals['faces_before']:,} -> "
                f"{totals['faces_after']:,} faces, {self.seconds:.1f} s>")

    @property
    def failed(self) -> bool:
        """True when any link has an error or warning finding (exit code 1)."""
        return any(f.severity in ("error", "warning")
                   for o in self.outcomes for f in o.report.findings)

    def totals(self) -> dict[str, Any]:
        """Sums over the links: faces before/after, their ratio, hulls, time."""
        reports = [o.report for o in self.outcomes if o.written]
        before = sum(r.faces_before for r in reports)
        after = sum(r.faces_after for r in reports)
        return {"links": len(self.outcomes), "written": len(reports), "faces_before": before,
                "faces_after": after, "reduction": (before / after) if after else None,
                "hulls": sum(r.hulls for r in reports),
                "primitives": sum(1 for o in self.outcomes if o.written
                                  for p in o.parts if isinstance(p, PrimitivePart)),
                "seconds": self.seconds,
                "worker_seconds": sum(o.report.seconds for o in self.outcomes),
                "cached": sum(1 for o in self.outcomes if o.report.cached)}

    def to_dict(self) -> dict[str, Any]:
        return {"robot": self.robot.name, "source": self.robot.source,
                "options": as_dict(self.options), "jobs": self.jobs,
                "links": [o.report.to_dict() for o in self.outcomes],
                "totals": self.totals(), "failed": self.failed}

