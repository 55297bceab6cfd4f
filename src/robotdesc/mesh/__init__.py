"""Meshes: resolve a `<mesh>` reference, load and validate the file, compute mass properties
and health, and cache the results by content hash. See docs/meshes.md.

The names below are imported on first use (PEP 562), so that `import robotdesc.mesh.cache`
or `robotdesc.mesh.context` does not pull numpy in: a warm lint, served from the cache,
never imports numpy, trimesh or scipy. Heavy readers are imported only when a file needs them.
"""

from __future__ import annotations

from robotdesc.lazy import lazy_exports

#: Public name -> the submodule defining it.
_EXPORTS = {
    "MeshCache": "cache", "default_cache_dir": "cache",
    "MeshHealth": "records", "MassMethod": "records", "MeshSummary": "records",
    "mesh_health": "health",
    "LoadedMesh": "load", "load_mesh": "load",
    "MassProperties": "properties", "combine": "properties",
    "link_mass_properties": "properties",
    "volume_integrals": "mass",
    "primitive_properties": "primitives",
    "MeshResolution": "resolve", "ResolveProblem": "resolve", "ResolveProblemKind": "resolve",
    "resolve_mesh": "resolve", "MeshLocator": "locate",
    "analyze_mesh_file": "analyze", "summarize": "summary",
    "MeshError": "errors", "MeshErrorKind": "errors", "MeshLimits": "errors",
}

__all__ = [
    "LoadedMesh", "MassMethod", "MassProperties", "MeshCache", "MeshError", "MeshErrorKind",
    "MeshHealth", "MeshLimits", "MeshLocator", "MeshResolution", "MeshSummary", "ResolveProblem",
    "ResolveProblemKind", "analyze_mesh_file", "combine", "default_cache_dir",
    "link_mass_properties", "load_mesh", "mesh_health", "primitive_properties",
    "resolve_mesh", "summarize", "volume_integrals",
]


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
