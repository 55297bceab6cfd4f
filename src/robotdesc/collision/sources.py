"""Each link's source geometry: its meshes resolved, loaded and placed in the link frame.

Meshes resolve under the rules lint uses (`robotdesc.mesh.resolve`): a `package://` file
stays inside its package, a relative path inside the package holding the file that names it
(after symlinks), and `file://` or absolute paths only when the config allows them. A
reference that breaks a rule is a problem of its link (a finding), never read.

The digest of a link's sources (file contents by hash, scale, origin, primitive sizes) is
computed without loading any mesh (through the mesh cache's stat index), so that an
unchanged link is served from the cache or checked in CI without reading its meshes.
"""

from __future__ import annotations

import hashlib
import json
import os
import stat
from dataclasses import dataclass
from typing import Callable

import numpy as np

from robotdesc.collision.tessellate import primitive_mesh, transform_points
from robotdesc.expansion.packages import enclosing_package
from robotdesc.mesh.resolve import resolve_mesh
from robotdesc.model.elements import MeshRef, Pose, Robot
from robotdesc.spatial import pose_matrix


@dataclass(frozen=True)
class SourceItem:
    """One geometry of a link: a resolved mesh file, or a primitive."""

    geometry: object
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


def link_sources(robot: Robot, source: str, find_package: Callable[[str], str | None],
                 allow_absolute: bool = False) -> list[LinkSources]:
    """The links that have geometry of the kind `source` ("visual" or "collision").

    Args:
        robot: the parsed robot.
        source: "visual" or "collision".
        find_package: package name -> root folder (the lint's resolver chain).
        allow_absolute: accept `file://` and absolute mesh paths (the config's
            `allow_absolute_paths`; off by default, as for lint).
    """
    roots: dict[str, str | None] = {}

    def package_root(folder: str) -> str | None:
        if folder not in roots:
            found = enclosing_package(folder)
            roots[folder] = str(found[1]) if found else None
        return roots[folder]

    result = []
    for link in robot.links:
        elements = link.visuals if source == "visual" else link.collisions
        items, problems = [], []
        for element in elements:
            if element.geometry is None:
                continue
            if isinstance(element.geometry, MeshRef):
                base = _base_dir(element, robot)
                found = resolve_mesh(element.geometry.filename, base_dir=base,
                                     find_package=find_package,
                                     allow_absolute=allow_absolute,
                                     relative_root=package_root(base))
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
                   parameters: dict) -> str | None:
    """The hash of a link's sources and the parameters; None when a file cannot be read."""
    entries = []
    for item in sources.items:
        entry = {"origin": [list(item.origin.xyz), list(item.origin.rpy)]}
        if item.path:
            digest = content_digest(item.path)
            if digest is None:
                return None
            entry.update(mesh=digest, scale=list(item.geometry.scale))
        else:
            entry.update(primitive=type(item.geometry).__name__,
                         dims=[v for k, v in vars(item.geometry).items() if k != "where"])
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
        matrix = pose_matrix(item.origin)
        if item.path:
            loaded = load_mesh(item.path, item.geometry.scale)
            flat = transform_points(matrix, loaded.triangles.reshape(-1, 3))
            soups.append(flat.reshape(-1, 3, 3))
        else:
            part = primitive_mesh(item.geometry, item.origin)
            soups.append(part.vertices[part.faces])
    return np.concatenate(soups)


def file_digest(path: str) -> str | None:
    """SHA-256 of a regular file's bytes (no cache); None when unreadable or not a regular
    file (opened without blocking: a FIFO never hangs)."""
    digest = hashlib.sha256()
    try:
        handle = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError:
        return None
    try:
        if not stat.S_ISREG(os.fstat(handle).st_mode):
            return None
        while chunk := os.read(handle, 1 << 20):
            digest.update(chunk)
    except OSError:
        return None
    finally:
        os.close(handle)
    return digest.hexdigest()


def _base_dir(element: object, robot: Robot) -> str:
    where = getattr(element, "where", None)
    if where is not None and where.span.path:
        return os.path.dirname(os.path.abspath(where.span.path))
    return os.path.dirname(os.path.abspath(robot.source)) if robot.source else os.getcwd()


