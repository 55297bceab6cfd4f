"""Mesh references -> mesh data MuJoCo can take: a file it reads itself, or vertex arrays.

MuJoCo reads STL (at most 200,000 faces), OBJ and MSH files. Everything else robotdesc reads
(COLLADA with its `<unit>` and node transforms, GLB/glTF, PLY), oversized STL files and
mirroring scales are loaded by robotdesc's own mesh loader and handed to MuJoCo as vertex and
face arrays in memory, so no temporary file is left behind. References are found by the one
mesh locator lint uses (`robotdesc.mesh.locate.MeshLocator`: package paths resolved by
robotdesc without ROS, a relative path from the file that wrote the `<mesh>`, absolute paths
only when the config allows them).

`SimMeshError` lives in `robotdesc.errors` with every other error; it is re-exported here, its
old home.
"""

from __future__ import annotations

import logging
import os
from dataclasses import dataclass

import numpy as np

from robotdesc.errors import MeshError, SimMeshError
from robotdesc.mesh.locate import MeshLocator
from robotdesc.model.elements import MeshRef
from robotdesc.source import Span

__all__ = ["MUJOCO_STL_FACE_LIMIT", "NATIVE_FORMATS", "MeshAsset", "MeshAssets", "SimMeshError",
           "indexed"]

log = logging.getLogger(__name__)

#: Extensions MuJoCo reads natively (lower case, no dot).
NATIVE_FORMATS = frozenset({"stl", "obj"})
#: MuJoCo's STL reader refuses files with more faces than this.
MUJOCO_STL_FACE_LIMIT = 200_000


@dataclass(frozen=True, eq=False)
class MeshAsset:
    """One mesh as MuJoCo will get it.

    Attributes:
        key: a stable name for the asset (unique per file and scale).
        file: a file MuJoCo reads itself (None when `vertices` are given).
        scale: the scale MuJoCo applies to `file` (the arrays are already scaled).
        vertices: (n, 3) float64 vertex positions in metres, or None.
        faces: (m, 3) int32 vertex indices, or None.
        source: the mesh file the asset comes from.
    """

    key: str
    file: str | None
    scale: tuple[float, float, float]
    vertices: np.ndarray | None = None
    faces: np.ndarray | None = None
    source: str = ""


class MeshAssets:
    """Resolves and converts the meshes of one robot, each file once.

    Args:
        locator: where each `<mesh>` leads (the rules of lint, under the config's policy).
    """

    def __init__(self, locator: MeshLocator) -> None:
        self.locator = locator
        self._assets: dict[tuple[str, tuple[float, float, float]], MeshAsset] = {}

    def asset(self, ref: MeshRef) -> MeshAsset:
        """The MuJoCo asset of a `<mesh>` reference.

        Raises:
            SimMeshError: the reference does not resolve or the file cannot be read.
        """
        resolution = self.locator.locate(ref)
        if resolution.path is None:
            problem = resolution.problem.message if resolution.problem else "does not resolve"
            raise SimMeshError(f"cannot simulate: {problem}", _span(ref))
        scale = (float(ref.scale[0]), float(ref.scale[1]), float(ref.scale[2]))
        key = (resolution.path, scale)
        if key not in self._assets:
            self._assets[key] = self._make(resolution.path, scale, ref, len(self._assets))
        return self._assets[key]

    def _make(self, path: str, scale: tuple[float, float, float], ref: MeshRef,
              index: int) -> MeshAsset:
        name = f"mesh{index}_{os.path.splitext(os.path.basename(path))[0]}"
        extension = os.path.splitext(path)[1].lower().lstrip(".")
        if extension in NATIVE_FORMATS and np.prod(scale) > 0 and _native_ok(path, extension):
            return MeshAsset(name, path, scale, source=path)
        from robotdesc.mesh.load import load_mesh

        try:
            loaded = load_mesh(path, scale)
        except MeshError as error:
            raise SimMeshError(f"cannot simulate: {error}", _span(ref)) from None
        vertices, faces = indexed(loaded.triangles)
        log.debug("%s: %d triangles converted for MuJoCo", path, len(faces))
        return MeshAsset(name, None, (1.0, 1.0, 1.0), vertices, faces, source=path)


def indexed(triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A triangle soup (n, 3, 3) as unique vertices (k, 3) and faces (n, 3)."""
    flat = np.ascontiguousarray(triangles.reshape(-1, 3), dtype=np.float64)
    vertices, inverse = np.unique(flat, axis=0, return_inverse=True)
    return vertices, inverse.reshape(-1, 3).astype(np.int32)


def _native_ok(path: str, extension: str) -> bool:
    """Whether MuJoCo's own reader takes this file (its STL reader caps the face count)."""
    if extension != "stl":
        return True
    try:
        size = os.path.getsize(path)
        with open(path, "rb") as handle:
            head = handle.read(84)
    except OSError:
        return False
    if len(head) < 84 or head[:5].lower() == b"solid" and (size - 84) % 50 != 0:
        return False  # ASCII STL: robotdesc's reader handles every dialect
    faces = int.from_bytes(head[80:84], "little")
    return 0 < faces <= MUJOCO_STL_FACE_LIMIT and size == 84 + 50 * faces


def _span(ref: MeshRef) -> Span | None:
    return ref.where.span if ref.where is not None else None
