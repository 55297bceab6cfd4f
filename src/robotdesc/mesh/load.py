"""Load a mesh file into one validated triangle soup in metres, URDF scale applied.

STL goes through the plain numpy reader (stl.py); COLLADA through pycollada, honouring the
document's `<unit meter=...>` and node transforms as Gazebo and RViz do (see docs/meshes.md);
OBJ, PLY, GLB and glTF through trimesh. Every body in a file is combined into one soup.
Whatever goes wrong becomes a `MeshError` naming the file, never a crash.
"""

from __future__ import annotations

import io
import logging
import os
import re
import stat
import warnings
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from robotdesc.errors import XmlSyntaxError
from robotdesc.mesh.stl import read_stl
from robotdesc.mesh.validate import (
    DEFAULT_LIMITS,
    MeshError,
    MeshErrorKind,
    MeshLimits,
    check_file_head,
    check_triangle_count,
    validate_indexed,
    validate_scale,
    validate_triangles,
)
from robotdesc.xml_input import XmlOptions, parse_xml

if TYPE_CHECKING:
    import collada  # pycollada (untyped); imported where a .dae is read

_COLLADA = XmlOptions(what="COLLADA file")
#: How the guarded parser's message for a text node over libxml2's limit begins.
_LONG_TEXT = "a text or attribute value longer than"

log = logging.getLogger(__name__)

#: File extensions (lower case, without the dot) and the reader that handles them.
FORMATS = {"stl": "stl", "dae": "collada", "obj": "trimesh", "ply": "trimesh",
           "glb": "trimesh", "gltf": "trimesh"}
_TEXT_FORMATS = {"dae", "obj", "gltf"}
#: A COLLADA `<bind_material>` (its material bindings only; no geometry is in it).
_BIND_MATERIAL = re.compile(rb"<bind_material\b(?:[^>]*/>|.*?</bind_material\s*>)", re.DOTALL)


@dataclass(frozen=True, eq=False)
class LoadedMesh:
    """A mesh file as one triangle soup.

    Attributes:
        triangles: (n, 3, 3) float64 vertex coordinates in metres, after the COLLADA unit and
            the URDF scale; wound as in the file (a mirroring scale is compensated).
        path: the file read.
        format: the file extension, lower case ("stl", "dae", ...).
        bodies: number of separate geometries combined (COLLADA/glTF nodes, OBJ objects).
        unit_meter: the COLLADA `<unit meter>` factor applied (1.0 for other formats).
        scale: the URDF scale applied.
        mirrored: the scale has a negative determinant; face winding was reversed so that
            outward normals stay outward.
        broken_references: material, effect or texture references of a COLLADA file that do
            not resolve; the geometry was read without them (as assimp, RViz's loader, does).
    """

    triangles: np.ndarray
    path: str
    format: str
    bodies: int = 1
    unit_meter: float = 1.0
    scale: tuple[float, float, float] = (1.0, 1.0, 1.0)
    mirrored: bool = False
    broken_references: tuple[str, ...] = ()


def load_mesh(path: str | os.PathLike[str], scale: Sequence[float] = (1.0, 1.0, 1.0),
              limits: MeshLimits = DEFAULT_LIMITS) -> LoadedMesh:
    """Read and validate a mesh file.

    Args:
        path: the mesh file (already resolved, see resolve.py).
        scale: the URDF `<mesh scale>` (x, y, z factors).
        limits: size limits checked before allocating.

    Returns:
        The file's triangles in metres.

    Raises:
        MeshError: unsupported format, LFS pointer, malformed or oversized file, non-finite
            coordinates, face indices out of range, bad scale.
    """
    name = os.fspath(path)
    factors = (float(scale[0]), float(scale[1]), float(scale[2]))
    validate_scale(factors, name)
    _check_regular_file(name)
    extension = os.path.splitext(name)[1].lower().lstrip(".")
    reader = FORMATS.get(extension)
    if not extension:
        raise MeshError(MeshErrorKind.UNSUPPORTED,
                        "has no file extension, so its format is unknown (supported: "
                        f"{', '.join('.' + e for e in sorted(FORMATS))})", name)
    if reader is None:
        raise MeshError(MeshErrorKind.UNSUPPORTED,
                        f"format '.{extension}' is not supported (supported: "
                        f"{', '.join('.' + e for e in sorted(FORMATS))})", name)
    broken: tuple[str, ...] = ()
    if reader == "stl":
        triangles, bodies, unit = read_stl(name, limits), 1, 1.0
    else:
        _check_head(name, limits, text=extension in _TEXT_FORMATS)
        if reader == "collada":
            triangles, bodies, unit, broken = _read_collada(name, limits)
        else:
            triangles, bodies, unit = _read_with_trimesh(name, extension, limits)
    factor = np.asarray(factors) * unit
    soup = np.asarray(triangles, dtype=np.float64) * factor
    mirrored = bool(np.prod(factor) < 0)
    if mirrored:
        soup = soup[:, ::-1].copy()
    validate_triangles(soup, name, limits)
    return LoadedMesh(soup, name, extension, bodies, unit, factors, mirrored, broken)


def _check_regular_file(name: str) -> None:
    """Refuse FIFOs, devices and directories before opening them (a FIFO would block)."""
    try:
        mode = os.stat(name).st_mode
    except OSError as error:
        raise MeshError(MeshErrorKind.UNREADABLE,
                        f"cannot be read: {error.strerror}", name) from error
    if not stat.S_ISREG(mode):
        raise MeshError(MeshErrorKind.UNREADABLE, "is not a regular file", name)


def _check_head(name: str, limits: MeshLimits, text: bool) -> None:
    try:
        size = os.path.getsize(name)
        with open(name, "rb") as handle:
            head = handle.read(256)
    except OSError as error:
        raise MeshError(MeshErrorKind.UNREADABLE,
                        f"cannot be read: {error.strerror}", name) from error
    check_file_head(head, size, name, limits, text=text)


def _read_collada(name: str, limits: MeshLimits
                  ) -> tuple[np.ndarray, int, float, tuple[str, ...]]:
    """Triangles of every geometry instance in the scene, node transforms applied, in the
    document's units; plus the body count, the `<unit meter>` factor and the broken
    material/texture references.

    pycollada drops a whole scene node whose `<bind_material>` names a material it cannot
    build (a missing effect or texture surface); assimp draws the geometry anyway. Such a
    file is read a second time without its material bindings, and the broken references
    are returned instead of the geometry being lost.
    """
    data = _read_bytes(name)
    try:  # the guarded parser first: no DOCTYPE or entity, depth and size limits
        parse_xml(data, name, _COLLADA)
    except XmlSyntaxError as error:
        if error.message.startswith(_LONG_TEXT):
            # a float_array over libxml2's 10 MB text limit is a large mesh, not a broken
            # one (assimp reads it); the DOCTYPE was refused before libxml2 ran, and the
            # file's size was checked against `max_text_bytes`
            log.debug("%s: %s; read by pycollada", name, error.message)
        else:
            where = f"line {error.span.line}: " if error.span and error.span.line else ""
            raise MeshError(MeshErrorKind.MALFORMED,
                            f"COLLADA could not be read: {where}{error.message}",
                            name) from None
    try:
        with warnings.catch_warnings():  # pycollada still builds numpy.matrix objects
            warnings.simplefilter("ignore", PendingDeprecationWarning)
            document = _collada_document(data)
            broken = _broken_references(document, name)
            if broken:
                document = _collada_document(_BIND_MATERIAL.sub(b"", data))
            unit = document.assetInfo.unitmeter if document.assetInfo else None
            parts = list(_collada_parts(document, name, limits))
    except MeshError:
        raise
    except Exception as error:  # pycollada raises many unrelated types on malformed input
        raise MeshError(MeshErrorKind.MALFORMED,
                        f"COLLADA could not be read: {error}", name) from error
    unit_meter = 1.0 if unit is None else float(unit)
    if not np.isfinite(unit_meter) or unit_meter <= 0:
        raise MeshError(MeshErrorKind.MALFORMED,
                        f"COLLADA <unit meter=\"{unit}\"> must be a positive number", name)
    if not parts:
        defined = len(document.geometries)
        detail = (f"; its scene places none of the {defined} geometries it defines, so a "
                  "viewer that follows the scene (RViz, Gazebo) draws nothing"
                  if defined and document.scene is not None else "")
        raise MeshError(MeshErrorKind.EMPTY, "COLLADA file contains no triangles" + detail, name)
    return (np.concatenate([p for _, p in parts]), len({body for body, _ in parts}),
            unit_meter, broken)


def _collada_document(data: bytes) -> collada.Collada:
    """A pycollada document; unsupported features and broken references are recorded in
    its `errors`, not raised."""
    import collada  # lazy: pycollada is only needed for .dae files

    return collada.Collada(io.BytesIO(data), ignore=[collada.common.DaeUnsupportedError,
                                                      collada.common.DaeBrokenRefError])


def _broken_references(document: collada.Collada, name: str) -> tuple[str, ...]:
    """pycollada's broken references, and texture images whose file does not exist."""
    import collada

    found = [str(error).removeprefix("DaeBrokenRefError: ") for error in document.errors
             if isinstance(error, collada.common.DaeBrokenRefError)]
    folder = os.path.dirname(name)
    for image in document.images:
        path = str(getattr(image, "path", "") or "")
        if path and "://" not in path and not os.path.isabs(path) \
                and not os.path.exists(os.path.join(folder, path)):
            found.append(f"texture image '{path}' does not exist")
    return tuple(dict.fromkeys(found))


def _collada_parts(document: collada.Collada, name: str,
                   limits: MeshLimits) -> Iterator[tuple[int, np.ndarray]]:
    """(body id, triangles) per bound primitive; all geometries untransformed if no scene."""
    import collada

    scene = document.scene
    if scene is not None:
        bound = list(scene.objects("geometry"))
    else:
        bound = [g.bind(np.identity(4), {}) for g in document.geometries]
    total = 0
    for body, geometry in enumerate(bound):
        matrix = np.asarray(getattr(geometry, "matrix", np.identity(4)), dtype=np.float64)
        inside_out = np.linalg.det(matrix[:3, :3]) < 0  # a mirroring node transform
        for primitive in geometry.primitives():
            if isinstance(primitive, collada.lineset.BoundLineSet):
                continue
            if not isinstance(primitive, collada.triangleset.BoundTriangleSet):
                primitive = primitive.triangleset()
            if primitive.vertex is None or primitive.vertex_index is None:
                continue
            vertices = np.asarray(primitive.vertex, dtype=np.float64)
            faces = np.asarray(primitive.vertex_index)
            if len(faces) == 0:
                continue
            total += len(faces)
            check_triangle_count(total, name, limits)
            validate_indexed(vertices, faces, name, limits)
            soup = vertices[faces]
            yield body, soup[:, ::-1] if inside_out else soup


def _read_bytes(name: str) -> bytes:
    try:
        with open(name, "rb") as handle:
            return handle.read()
    except OSError as error:
        raise MeshError(MeshErrorKind.UNREADABLE,
                        f"cannot be read: {error.strerror}", name) from error


def _text_as_utf8(name: str) -> str | io.BytesIO:
    """An OBJ that is not UTF-8 (a Latin-1 comment or name), transcoded so that trimesh
    never guesses its encoding; UTF-8 files are read from their path as usual."""
    data = _read_bytes(name)
    try:
        data.decode("utf-8")
    except UnicodeDecodeError:
        log.debug("%s is not UTF-8; read as Latin-1", name)
        return io.BytesIO(data.decode("latin-1").encode("utf-8"))
    return name


def _read_with_trimesh(name: str, extension: str,
                       limits: MeshLimits) -> tuple[np.ndarray, int, float]:
    import trimesh  # lazy: heavy import, only for formats the numpy readers do not cover

    try:
        scene = trimesh.load_scene(_text_as_utf8(name) if extension == "obj" else name,
                                   file_type=extension, process=False)
        pieces = []
        for node in scene.graph.nodes_geometry:
            transform, geometry_name = scene.graph[node]
            geometry = scene.geometry.get(geometry_name)
            if not isinstance(geometry, trimesh.Trimesh) or len(geometry.faces) == 0:
                continue
            vertices = np.asarray(geometry.vertices, dtype=np.float64)
            faces = np.asarray(geometry.faces)
            validate_indexed(vertices, faces, name, limits)
            soup = vertices[faces]
            if not np.allclose(transform, np.identity(4)):
                soup = soup @ np.asarray(transform[:3, :3]).T + np.asarray(transform[:3, 3])
                if np.linalg.det(transform[:3, :3]) < 0:
                    soup = soup[:, ::-1]
            pieces.append(soup)
    except MeshError:
        raise
    except Exception as error:  # trimesh's loaders raise many unrelated types
        raise MeshError(MeshErrorKind.MALFORMED,
                        f"could not be read: {error}", name) from error
    if not pieces:
        raise MeshError(MeshErrorKind.EMPTY, "contains no triangles", name)
    return np.concatenate(pieces), len(pieces), 1.0
