"""Why a mesh file could not be used, and the size limits a mesh file must respect.

Plain Python (no numpy): the mesh cache stores and serves these errors on warm runs.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from robotdesc.errors import InputError
from robotdesc.source import Span


class MeshErrorKind(str, enum.Enum):
    """Why a mesh file could not be read."""

    LFS_POINTER = "lfs-pointer"
    TRUNCATED = "truncated"
    TOO_LARGE = "too-large"
    NON_FINITE = "non-finite"
    BAD_INDEX = "bad-index"
    MALFORMED = "malformed"
    EMPTY = "empty"
    UNSUPPORTED = "unsupported-format"
    BAD_SCALE = "bad-scale"
    UNREADABLE = "unreadable"


class MeshError(InputError):
    """A mesh file is malformed, oversized or not a mesh at all.

    Args:
        kind: the machine-readable reason.
        message: what is wrong, in a user's words (the file name is prepended).
        path: the mesh file.
        span: where the `<mesh>` element is, when the caller knows it.
    """

    def __init__(self, kind: MeshErrorKind, message: str, path: str = "",
                 span: Span | None = None) -> None:
        text = f"{path}: {message}" if path else message
        super().__init__(text, span)
        self.kind = kind
        self.path = path
        self.detail = message


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
