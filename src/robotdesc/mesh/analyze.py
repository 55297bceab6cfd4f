"""A mesh file's summary, through the cache: the edge where mesh files are read.

Plain Python at import: on a cache hit nothing else is imported, so a warm lint never loads
numpy, trimesh or scipy. Only a miss imports the loaders and `robotdesc.mesh.summary`.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import TYPE_CHECKING

from robotdesc.mesh.errors import DEFAULT_LIMITS, MeshError, MeshLimits
from robotdesc.mesh.records import MeshSummary

if TYPE_CHECKING:
    from robotdesc.mesh.cache import MeshCache


def analyze_mesh_file(path: str | os.PathLike[str], scale: Sequence[float] = (1.0, 1.0, 1.0),
                      limits: MeshLimits = DEFAULT_LIMITS,
                      cache: MeshCache | None = None,
                      computed: MeshSummary | MeshError | None = None) -> MeshSummary:
    """Load and summarize a mesh file, through the cache when one is given.

    Args:
        path: the mesh file.
        scale: the URDF `<mesh scale>` applied to its coordinates.
        limits: size limits for reading it.
        cache: where summaries are kept by content hash and scale; None computes afresh.
        computed: the file's summary (or mesh error) already computed from these arguments
            (`robotdesc.mesh.prefetch`): used, and stored, on a cache miss.

    Raises:
        MeshError: the file cannot be used as a mesh (also served from the cache).
    """
    name = os.fspath(path)
    key = cache.key_for(name, scale) if cache is not None else None
    if cache is not None and key is not None:
        hit = cache.get(key, name)
        if hit is not None:
            if isinstance(hit, MeshError):
                raise hit
            return hit
    try:
        if isinstance(computed, MeshError):
            raise computed
        summary = computed if computed is not None else summarize_file(name, scale, limits)
    except MeshError as error:
        if cache is not None and key is not None:
            cache.put_error(key, error)
        raise
    if cache is not None and key is not None:
        cache.put(key, summary)
    return summary


def summarize_file(name: str, scale: Sequence[float], limits: MeshLimits) -> MeshSummary:
    """Load and summarize a mesh file (no cache).

    Raises:
        MeshError: the file cannot be used as a mesh.
    """
    from robotdesc.mesh.load import load_mesh  # lazy: numpy and the format readers
    from robotdesc.mesh.summary import summarize

    return summarize(load_mesh(name, scale, limits))
