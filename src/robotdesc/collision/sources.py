"""Each link's source geometry: its meshes resolved, loaded and placed in the link frame.

Meshes resolve through the one locator lint uses (`robotdesc.mesh.locate.MeshLocator`): a
`package://` file stays inside its package, a relative path is taken from the file that wrote
the `<mesh>` and stays inside its package (after symlinks), and `file://` or absolute paths
are accepted only when the config allows them. A reference that breaks a rule is a problem of
its link (a finding), never read.

The digest of a link's sources (file contents by hash, scale, origin, primitive sizes) is
computed without loading any mesh (through the mesh cache's stat index), so that an
unchanged link is served from the cache or checked in CI without reading its meshes.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from robotdesc.collision.tessellate import primitive_mesh, transform_points
from robotdesc.mesh.locate import MeshLocator
from robotdesc.model.elements import Geometry, MeshRef, Pose, Robot
from robotdesc.spatial import pose_matrix


@dataclass(frozen=True)
class SourceItem:
    """One geometry of a link: a resolved mesh file, or a primitive."""

    geometry: Geometry
    origin: Pose
    path: str | None = None
    problem: str | None = None


@dataclass(frozen=True)
class LinkSources:
    """A link's geometries to derive collision geometry from.

    Attributes:
        link: the link name.
        items: the geometries (visual or collision, per the option `source`).
        problems: references that do not resolve (the link cannot be processed).
    """

    link: str
    items: tuple[SourceItem, ...]
    problems: tuple[str, ...] = ()

    @property
    def mesh_paths(self) -> tuple[str, ...]:
        return tuple(i.path for i in self.items if i.path)


def link_sources(robot: Robot, source: str, meshes: MeshLocator) -> list[LinkSources]:
    """The links that have geometry of the kind `source` ("visual" or "collision").

    Args:
        robot: the parsed robot.
        source: "visual" or "collision".
        meshes: where each `<mesh>` leads (the lint's package resolver chain and the
            config's `allow_absolute_paths`).
    """
    result = []
    for link in robot.links:
        elements = link.visuals if source == "visual" else link.collisions
        items: list[SourceItem] = []
        problems: list[str] = []
        for element in elements:
            if element.geometry is None:
                continue
            if isinstance(element.geometry, MeshRef):
                found = meshes.locate(element.geometry)
                if not found.ok:
                    problems.append(found.problem.message if found.problem else "unresolved")
                    continue
                items.append(SourceItem(element.geometry, element.origin, found.path))
            else:
                items.append(SourceItem(element.geometry, element.origin))
        if items or problems:
            result.append(LinkSources(link.name, tuple(items), tuple(problems)))
    return result


def sources_digest(sources: LinkSources, content_digest: Callable[[str], str | None],
                   parameters: Mapping[str, object]) -> str | None:
    """The hash of a link's sources and the parameters; None when a file cannot be read or
    a reference does not resolve (such a link fails on its own, never shares a result)."""
    if sources.problems:
        return None
    entries: list[dict[str, object]] = []
    for item in sources.items:
        geometry = item.geometry
        entry: dict[str, object] = {"origin": [list(item.origin.xyz), list(item.origin.rpy)]}
        if isinstance(geometry, MeshRef) and item.path:
            digest = content_digest(item.path)
            if digest is None:
                return None
            entry.update(mesh=digest, scale=list(geometry.scale))
        else:
            entry.update(primitive=type(geometry).__name__,
                         dims=[v for k, v in vars(geometry).items() if k != "where"])
        entries.append(entry)
    text = json.dumps({"sources": entries, "parameters": parameters}, sort_keys=True,
                      default=repr)
    return hashlib.sha256(text.encode()).hexdigest()


def load_link_soup(sources: LinkSources) -> np.ndarray:
    """The link's geometries as one (n, 3, 3) triangle soup in the link frame (m).

    Raises:
        robotdesc.mesh.validate.MeshError: a mesh file cannot be used.
        ValueError: a primitive has a non-positive dimension.
    """
    from robotdesc.mesh.load import load_mesh

    soups = []
    for item in sources.items:
        geometry = item.geometry
        if isinstance(geometry, MeshRef):
            if item.path is None:
                continue  # never: an unresolved reference is a problem of the link, not an item
            loaded = load_mesh(item.path, geometry.scale)
            flat = transform_points(pose_matrix(item.origin), loaded.triangles.reshape(-1, 3))
            soups.append(flat.reshape(-1, 3, 3))
        else:
            part = primitive_mesh(geometry, item.origin)
            soups.append(part.vertices[part.faces])
    return np.concatenate(soups)
