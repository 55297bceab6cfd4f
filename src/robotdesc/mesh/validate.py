"""Checks a mesh must pass before any C extension sees it, and the error they raise.

Every loader funnels its arrays through `validate_triangles` or `validate_indexed`, so that
non-finite coordinates, out-of-range face indices and oversized inputs become a `MeshError`
(an `InputError`: a finding at the `<mesh>` line) rather than a crash or a huge allocation.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np

from robotdesc.errors import InputError
from robotdesc.source import Span

#: The first bytes of a Git LFS pointer file (a checkout without `git lfs pull`).
LFS_POINTER_PREFIX = b"version https://git-lfs.github.com/spec/"


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


def is_lfs_pointer(head: bytes) -> bool:
    """True when the first bytes of a file are a Git LFS pointer's."""
    return head.lstrip().startswith(LFS_POINTER_PREFIX)


def check_file_head(head: bytes, size: int, path: str, limits: MeshLimits,
                    text: bool = False) -> None:
    """Refuse LFS pointers, empty and oversized files from their first bytes and size.

    Args:
        text: the file is parsed as text (the lower `max_text_bytes` limit applies).

    Raises:
        MeshError: with kind LFS_POINTER, EMPTY or TOO_LARGE.
    """
    if is_lfs_pointer(head):
        raise MeshError(MeshErrorKind.LFS_POINTER,
                        "is a Git LFS pointer, not a mesh (run `git lfs pull`)", path)
    if size == 0:
        raise MeshError(MeshErrorKind.EMPTY, "is empty", path)
    limit = limits.max_text_bytes if text else limits.max_file_bytes
    if size > limit:
        raise MeshError(MeshErrorKind.TOO_LARGE,
                        f"is {size} bytes, over the limit of {limit}", path)


def check_triangle_count(count: int, path: str, limits: MeshLimits) -> None:
    """Refuse a triangle count over the limit before anything is allocated for it."""
    if count > limits.max_triangles:
        raise MeshError(MeshErrorKind.TOO_LARGE,
                        f"has {count} triangles, over the limit of {limits.max_triangles}", path)


def validate_triangles(triangles: np.ndarray, path: str, limits: MeshLimits) -> None:
    """Check a triangle soup: shape (n, 3, 3), finite, within the coordinate limit.

    Raises:
        MeshError: with kind EMPTY, MALFORMED, NON_FINITE or TOO_LARGE.
    """
    if triangles.ndim != 3 or triangles.shape[1:] != (3, 3):
        raise MeshError(MeshErrorKind.MALFORMED,
                        f"triangle array has shape {triangles.shape}, expected (n, 3, 3)", path)
    if len(triangles) == 0:
        raise MeshError(MeshErrorKind.EMPTY, "contains no triangles", path)
    check_triangle_count(len(triangles), path, limits)
    _check_coordinates(triangles, path, limits)


def validate_indexed(vertices: np.ndarray, faces: np.ndarray, path: str,
                     limits: MeshLimits) -> None:
    """Check an indexed mesh: finite vertices (V, 3), integer faces (F, 3) within [0, V).

    Raises:
        MeshError: with kind EMPTY, MALFORMED, NON_FINITE, BAD_INDEX or TOO_LARGE.
    """
    if vertices.ndim != 2 or vertices.shape[1] != 3:
        raise MeshError(MeshErrorKind.MALFORMED,
                        f"vertex array has shape {vertices.shape}, expected (n, 3)", path)
    if faces.ndim != 2 or faces.shape[1] != 3:
        raise MeshError(MeshErrorKind.MALFORMED,
                        f"face array has shape {faces.shape}, expected (n, 3)", path)
    if not np.issubdtype(faces.dtype, np.integer):
        raise MeshError(MeshErrorKind.BAD_INDEX, f"face indices are of type {faces.dtype}", path)
    if len(faces) == 0:
        raise MeshError(MeshErrorKind.EMPTY, "contains no triangles", path)
    check_triangle_count(len(faces), path, limits)
    low, high = int(faces.min()), int(faces.max())
    if low < 0 or high >= len(vertices):
        raise MeshError(MeshErrorKind.BAD_INDEX,
                        f"face index out of range: {low if low < 0 else high} "
                        f"(the mesh has {len(vertices)} vertices)", path)
    _check_coordinates(vertices, path, limits)


def validate_scale(scale: tuple[float, float, float], path: str) -> None:
    """A URDF mesh scale must be three finite, non-zero numbers.

    Raises:
        MeshError: with kind BAD_SCALE.
    """
    values = np.asarray(scale, dtype=float)
    if values.shape != (3,) or not np.all(np.isfinite(values)) or np.any(values == 0.0):
        raise MeshError(MeshErrorKind.BAD_SCALE,
                        f"scale {tuple(scale)} must be three finite non-zero numbers", path)


def _check_coordinates(values: np.ndarray, path: str, limits: MeshLimits) -> None:
    if not np.isfinite(values).all():
        bad = int(np.count_nonzero(~np.isfinite(values)))
        raise MeshError(MeshErrorKind.NON_FINITE,
                        f"has {bad} non-finite (NaN or infinite) coordinates", path)
    largest = float(np.abs(values).max()) if values.size else 0.0
    if largest > limits.max_coordinate:
        raise MeshError(MeshErrorKind.TOO_LARGE,
                        f"has a coordinate of {largest:g}, over the limit of "
                        f"{limits.max_coordinate:g}", path)
