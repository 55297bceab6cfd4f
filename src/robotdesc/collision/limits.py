"""What physics engines accept, as options: a result over a limit is a finding, never a
silent clamp.

Presets (see docs/collision.md for sources): PhysX cooks convex meshes of at most 255
vertices and 255 polygons and simulates triangle meshes only on static actors; MuJoCo
replaces every mesh geom by its convex hull for collisions (a non-convex mesh collides as
its hull); Bullet accepts both, but recommends small hulls (about 100 vertices) for speed.
"""

from __future__ import annotations

from dataclasses import dataclass

from robotdesc.collision.result import Finding, MeshPart, Part


@dataclass(frozen=True)
class EngineLimits:
    """Upper bounds a link's collision geometry must respect.

    Attributes:
        name: the preset's name ("custom" when edited).
        max_hulls: convex pieces per link.
        max_hull_vertices: vertices of one convex piece.
        max_mesh_faces: triangles of one non-convex mesh (decimate).
        convex_only: the engine collides convex shapes only (a non-convex mesh is a finding).
    """

    name: str = "physx"
    max_hulls: int = 64
    max_hull_vertices: int = 255
    max_mesh_faces: int = 20_000
    convex_only: bool = False


#: Presets by name; "physx" is the default (the strictest common hull limit).
ENGINE_LIMITS: dict[str, EngineLimits] = {
    "physx": EngineLimits("physx", max_hulls=64, max_hull_vertices=255, max_mesh_faces=20_000),
    "mujoco": EngineLimits("mujoco", max_hulls=64, max_hull_vertices=1000,
                           max_mesh_faces=200_000, convex_only=True),
    "bullet": EngineLimits("bullet", max_hulls=64, max_hull_vertices=100,
                           max_mesh_faces=50_000),
}


def limit_findings(parts: tuple[Part, ...], limits: EngineLimits) -> tuple[Finding, ...]:
    """Findings (warnings) for every limit a link's geometry exceeds."""

    meshes = [p for p in parts if isinstance(p, MeshPart)]
    hulls = [p for p in meshes if p.convex]
    found = []
    if len(hulls) > limits.max_hulls:
        found.append(Finding("over-limit", "warning",
                             f"{len(hulls)} convex hulls, over the {limits.name} limit of "
                             f"{limits.max_hulls} per link"))
    biggest = max((len(p.vertices) for p in hulls), default=0)
    if biggest > limits.max_hull_vertices:
        found.append(Finding("over-limit", "warning",
                             f"a convex hull has {biggest} vertices, over the {limits.name} "
                             f"limit of {limits.max_hull_vertices}"))
    for part in meshes:
        if part.convex:
            continue
        if len(part.faces) > limits.max_mesh_faces:
            found.append(Finding("over-limit", "warning",
                                 f"a mesh has {len(part.faces)} faces, over the {limits.name} "
                                 f"limit of {limits.max_mesh_faces}"))
        if limits.convex_only:
            found.append(Finding("not-convex", "warning",
                                 f"{limits.name} collides a mesh as its convex hull; this "
                                 "non-convex mesh will not collide as written"))
    return tuple(found)
