"""A plain numpy STL reader (binary and ASCII) that returns a triangle soup.

Mass properties need no vertex merge, which is most of the time a general mesh loader spends
on an STL. The binary header's triangle count is trusted only when it matches the file size
exactly, so a corrupt or hostile header never decides how much memory is allocated.
"""

from __future__ import annotations

import os
import re
from typing import BinaryIO

import numpy as np

from robotdesc.mesh.validate import (
    DEFAULT_LIMITS,
    MeshError,
    MeshErrorKind,
    MeshLimits,
    check_file_head,
    check_triangle_count,
    validate_triangles,
)

_HEADER_BYTES = 80
_COUNT_BYTES = 4
_RECORD_BYTES = 50
_RECORD = np.dtype([("normal", "<f4", (3,)), ("vertices", "<f4", (3, 3)), ("attr", "<u2")])
_NUMBER = rb"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|[-+]?(?:nan|inf(?:inity)?))"
_VERTEX = re.compile(rb"vertex\s+" + _NUMBER + rb"\s+" + _NUMBER + rb"\s+" + _NUMBER,
                     re.IGNORECASE)
_FACET = re.compile(rb"\bfacet\b", re.IGNORECASE)


def read_stl(path: str | os.PathLike[str], limits: MeshLimits = DEFAULT_LIMITS) -> np.ndarray:
    """Read an STL file into a triangle soup.

    Args:
        path: the STL file.
        limits: size limits checked before anything is allocated.

    Returns:
        float32 array of shape (n, 3, 3): n triangles, 3 vertices, xyz in file units.

    Raises:
        MeshError: LFS pointer, truncated or oversized file, malformed ASCII, non-finite
            coordinates, or no triangles.
    """
    name = os.fspath(path)
    try:
        size = os.path.getsize(name)
        with open(name, "rb") as handle:
            head = handle.read(_HEADER_BYTES + _COUNT_BYTES)
            check_file_head(head, size, name, limits)
            if _is_binary(head, size):
                triangles = _read_binary(handle, size, name, limits)
            elif head.lstrip()[:5].lower() == b"solid":
                check_file_head(head, size, name, limits, text=True)
                handle.seek(0)
                triangles = _parse_ascii(handle.read(), name, limits)
            else:
                triangles = None
    except OSError as error:
        raise MeshError(MeshErrorKind.UNREADABLE,
                        f"cannot be read: {error.strerror}", name) from error
    if triangles is None:
        raise _size_mismatch(head, size, name)
    validate_triangles(triangles, name, limits)
    return triangles


def _is_binary(head: bytes, size: int) -> bool:
    """Binary when the header count matches the file size exactly (even if it says 'solid')."""
    if len(head) < _HEADER_BYTES + _COUNT_BYTES:
        return False
    count = int.from_bytes(head[_HEADER_BYTES:], "little")
    return size == _HEADER_BYTES + _COUNT_BYTES + _RECORD_BYTES * count


def _read_binary(handle: BinaryIO, size: int, name: str, limits: MeshLimits) -> np.ndarray:
    count = (size - _HEADER_BYTES - _COUNT_BYTES) // _RECORD_BYTES
    check_triangle_count(count, name, limits)
    records = np.fromfile(handle, dtype=_RECORD, count=count)
    if len(records) != count:
        raise MeshError(MeshErrorKind.TRUNCATED,
                        f"ended after {len(records)} of {count} triangles", name)
    return np.ascontiguousarray(records["vertices"])


def _size_mismatch(head: bytes, size: int, name: str) -> MeshError:
    if len(head) < _HEADER_BYTES + _COUNT_BYTES:
        return MeshError(MeshErrorKind.TRUNCATED,
                         f"is {size} bytes, shorter than a binary STL header", name)
    claimed = int.from_bytes(head[_HEADER_BYTES:], "little")
    expected = _HEADER_BYTES + _COUNT_BYTES + _RECORD_BYTES * claimed
    what = "truncated" if size < expected else "longer than its header says"
    return MeshError(MeshErrorKind.TRUNCATED,
                     f"binary STL header claims {claimed} triangles ({expected} bytes) but the "
                     f"file has {size} bytes ({what})", name)


def _parse_ascii(data: bytes, name: str, limits: MeshLimits) -> np.ndarray:
    """Parse ASCII STL: every `vertex x y z`, three per facet."""
    if b"\0" in data[:4096]:
        raise MeshError(MeshErrorKind.MALFORMED,
                        "starts with 'solid' but is neither ASCII STL nor a binary STL whose "
                        "header count matches the file size", name)
    facets = len(_FACET.findall(data))
    check_triangle_count(facets, name, limits)
    numbers = _VERTEX.findall(data)
    if facets == 0 or len(numbers) != 3 * facets:
        raise MeshError(MeshErrorKind.MALFORMED,
                        f"ASCII STL has {facets} facets but {len(numbers)} vertices "
                        "(expected three per facet)", name)
    try:
        values = np.array(numbers, dtype=np.float64)
    except ValueError as error:
        raise MeshError(MeshErrorKind.MALFORMED,
                        f"ASCII STL number unreadable: {error}", name) from error
    return values.reshape(facets, 3, 3)
