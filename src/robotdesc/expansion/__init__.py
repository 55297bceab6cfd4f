"""Expansion: xacro (or a plain URDF) to a URDF document with source provenance.

`expand_file` is the one entry point. Xacro runs in an isolated worker process (see
`robotdesc.expansion.worker`); results are cached by the content of every file read.

The names below are imported on first use (PEP 562): the worker process imports
`robotdesc.expansion.worker` through this package, and must not pay for the parent's side
(the cache, hashing, the answer's checks) in its start-up.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from robotdesc.lazy import lazy_exports

if TYPE_CHECKING:
    from robotdesc.expansion.expand import (
        DEFAULT_ENV_ALLOWLIST,
        MAX_URDF_BYTES,
        ExpandOptions,
        expand_file,
        holds_substitutions,
        is_xacro,
        looks_binary,
    )
    from robotdesc.expansion.result import Expanded, ResolvedPackage

#: Where each name of the package is defined.
_EXPORTS = {
    "DEFAULT_ENV_ALLOWLIST": "robotdesc.expansion.expand",
    "MAX_URDF_BYTES": "robotdesc.expansion.expand",
    "ExpandOptions": "robotdesc.expansion.expand",
    "Expanded": "robotdesc.expansion.result",
    "ResolvedPackage": "robotdesc.expansion.result",
    "expand_file": "robotdesc.expansion.expand",
    "holds_substitutions": "robotdesc.expansion.expand",
    "is_xacro": "robotdesc.expansion.expand",
    "looks_binary": "robotdesc.expansion.expand",
}

__all__ = ["DEFAULT_ENV_ALLOWLIST", "MAX_URDF_BYTES", "ExpandOptions", "Expanded", "ResolvedPackage",
           "expand_file", "holds_substitutions", "is_xacro", "looks_binary"]


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
