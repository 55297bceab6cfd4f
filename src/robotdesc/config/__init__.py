"""robotdesc's configuration: `[tool.robotdesc]` in pyproject.toml, or robotdesc.toml.

The configuration that applies to a file is the first one found walking up from the file's
directory: in each directory robotdesc.toml (its top-level table) wins over pyproject.toml
(its `[tool.robotdesc]` table; a pyproject.toml without that table is skipped). The walk stops
after a directory that holds a VCS root (`.git`, `.hg`, `.svn`) or at the filesystem root.

Example (pyproject.toml)::

    [tool.robotdesc]
    select = ["ALL"]
    ignore = ["G"]                 # codes, prefixes ("J", "J1") or rule names
    fail-on = "warning"            # error | warning | info (default: info, any finding)
    [tool.robotdesc.per-file-ignores]
    "vendor/*.xacro" = ["S"]
    [tool.robotdesc.rules.X101]    # a rule's options, checked against its options dataclass
    max_depth = 8
    [tool.robotdesc.severity]
    J107 = "error"
    [tool.robotdesc.packages]      # package name -> directory, relative to this file
    my_robot_description = "src/my_robot_description"
    [tool.robotdesc.args]          # default xacro arguments
    use_gazebo = "false"
    [tool.robotdesc.meshes]        # mesh and inertia settings (see MeshSettings)
    inertia-source = "collision"   # or "visual": the geometry mass properties come from
    expected-mass = 16.3           # kg, checked by B101 (mass-budget)
    mass-tolerance = 0.05          # relative
    allow-absolute-paths = false   # accept file:// and absolute mesh paths
    collision-triangle-budget = 10000
    cache = true                   # cache mesh summaries (see docs/meshes.md)
    [[tool.robotdesc.targets]]     # what a directory lint checks; each matrix variant apart
    file = "urdf/ur.urdf.xacro"
    args = { safety_limits = "true" }
    matrix = { ur_type = ["ur5e", "ur10e"] }

One module per job: `schema` (what a config holds), `discovery` (which file applies, and
loading it), `parse` (its text and TOML), `validate` (a table -> `Config`), `coerce` (a value
against a type hint), `locate` (a key's TOML line, named by every `ConfigError`); the
`[meshes]` table is `robotdesc.mesh.settings.MeshSettings`, re-exported here.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from robotdesc.lazy import lazy_exports

if TYPE_CHECKING:
    from robotdesc.config.discovery import discover_config, load_config
    from robotdesc.config.files import CONFIG_FILES, VCS_MARKERS, find_config_file
    from robotdesc.config.parse import MAX_TOML_DEPTH
    from robotdesc.config.schema import Config, SimSettings, TargetSpec
    from robotdesc.config.validate import config_from_mapping
    from robotdesc.mesh.settings import MeshSettings  # the `[meshes]` table (Config.meshes)

#: Where each name of the package is defined: imported on first use, so that the replay of an
#: unchanged lint can ask `config.files` without loading the schema and its validation.
_EXPORTS = {
    "CONFIG_FILES": "robotdesc.config.files",
    "MAX_TOML_DEPTH": "robotdesc.config.parse",
    "VCS_MARKERS": "robotdesc.config.files",
    "Config": "robotdesc.config.schema",
    "MeshSettings": "robotdesc.mesh.settings",
    "SimSettings": "robotdesc.config.schema",
    "TargetSpec": "robotdesc.config.schema",
    "config_from_mapping": "robotdesc.config.validate",
    "discover_config": "robotdesc.config.discovery",
    "find_config_file": "robotdesc.config.files",
    "load_config": "robotdesc.config.discovery",
}

__all__ = [
    "CONFIG_FILES",
    "MAX_TOML_DEPTH",
    "VCS_MARKERS",
    "Config",
    "MeshSettings",
    "SimSettings",
    "TargetSpec",
    "config_from_mapping",
    "discover_config",
    "find_config_file",
    "load_config",
]


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
