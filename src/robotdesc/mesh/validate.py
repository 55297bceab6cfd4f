"""Checks a mesh must pass before any C extension sees it, and the error they raise.

Every loader funnels its arrays through `validate_triangles` or `validate_indexed`, so that
non-finite coordinates, out-of-range face indices and oversized inputs become a `MeshError`
(an `InputError`: a finding at the `<mesh>` line) rather than a crash or a huge allocation.
"""

from __future__ import annotations

import numpy as np

from robotdesc.mesh.errors import DEFAULT_LIMITS, MeshError, MeshErrorKind, MeshLimits

__all__ = ["DEFAULT_LIMITS", "LFS_POINTER_PREFIX", "MeshError", "MeshErrorKind", "MeshLimits",
           "check_file_head", "check_triangle_count", "is_lfs_pointer", "validate_indexed",
           "validate_scale", "validate_triangles"]

#: The first bytes of a Git LFS pointer file (a checkout without `git lfs pull`).
LFS_POINTER_PREFIX = b"version https://git-lfs.github.com/spec/"


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
