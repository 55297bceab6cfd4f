"""The size limits a mesh file must respect.

`MeshError` and `MeshErrorKind` (why a mesh file could not be used) live in
`robotdesc.errors` with every other error; they are re-exported here for the mesh modules
that import them from this module. Plain Python (no numpy).
"""

from __future__ import annotations

from dataclasses import dataclass

from robotdesc.errors import MeshError, MeshErrorKind

__all__ = ["DEFAULT_LIMITS", "MeshError", "MeshErrorKind", "MeshLimits"]


@dataclass(frozen=True)
class MeshLimits:
    """Upper bounds on what a mesh file may make robotdesc allocate.

    Attributes:
        max_file_bytes: largest mesh file read, in bytes.
        max_text_bytes: largest text mesh file (ASCII STL, OBJ, DAE) parsed, in bytes; text
            parsers need several times the file size in memory.
        max_triangles: largest triangle count accepted (after triangulation).
        max_coordinate: largest absolute coordinate accepted, in file units.
    """

    max_file_bytes: int = 512 * 1024 * 1024
    max_text_bytes: int = 128 * 1024 * 1024
    max_triangles: int = 20_000_000
    max_coordinate: float = 1e9


#: The limits used when a caller names none.
DEFAULT_LIMITS = MeshLimits()
