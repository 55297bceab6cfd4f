"""Meshes: resolve a `<mesh>` reference, load and validate the file, compute mass properties
and health, and cache the results by content hash. See docs/meshes.md.

Heavy readers (pycollada, trimesh, scipy) are imported only when a file needs them.
"""

from robotdesc.mesh.cache import MeshCache, default_cache_dir
from robotdesc.mesh.health import MeshHealth, mesh_health
from robotdesc.mesh.load import LoadedMesh, load_mesh
from robotdesc.mesh.mass import (
    MassProperties,
    combine,
    link_mass_properties,
    rpy_matrix,
    volume_integrals,
)
from robotdesc.mesh.primitives import primitive_properties
from robotdesc.mesh.resolve import MeshResolution, ResolveProblem, ResolveProblemKind, resolve_mesh
from robotdesc.mesh.summary import MassMethod, MeshSummary, analyze_mesh_file, summarize
from robotdesc.mesh.validate import MeshError, MeshErrorKind, MeshLimits

__all__ = [
    "LoadedMesh", "MassMethod", "MassProperties", "MeshCache", "MeshError", "MeshErrorKind",
    "MeshHealth", "MeshLimits", "MeshResolution", "MeshSummary", "ResolveProblem",
    "ResolveProblemKind", "analyze_mesh_file", "combine", "default_cache_dir",
    "link_mass_properties", "load_mesh", "mesh_health", "primitive_properties",
    "resolve_mesh", "rpy_matrix", "summarize", "volume_integrals",
]
