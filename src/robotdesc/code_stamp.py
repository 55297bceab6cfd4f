"""The identity of robotdesc's code and of the backends a finding depends on: part of the key
of every cache, so that a changed robotdesc or an upgraded backend never serves results an
older build computed."""

from __future__ import annotations

import functools
import hashlib
import importlib.util
import os

from robotdesc._version import __version__

#: Backends whose version can change what a lint finds (their installed file stands for it,
#: `module_stamp`): part of the key of every cache that stores findings.
FINDING_BACKENDS = ("xacro", "lxml", "numpy", "trimesh", "collada", "pinocchio", "coal",
                    "manifold3d")


@functools.cache
def code_id() -> str:
    """The version plus a digest of every module's path, size and modification time.

    Caches key their entries with it, so that a changed robotdesc (an editable install, a
    rebuilt wheel with the same version) never serves results an older build computed.
    Costs one `stat` per module (about 200), a millisecond or two.
    """
    package = os.path.dirname(os.path.abspath(__file__))
    digest = hashlib.sha256(__version__.encode())
    skip = len(package) + 1  # the path relative to the package, as one slice (no relpath)
    for folder, subfolders, files in os.walk(package):
        subfolders[:] = sorted(name for name in subfolders if name != "__pycache__")
        for name in sorted(files):
            if name.endswith((".py", ".js")):
                path = f"{folder}/{name}"
                try:
                    status = os.stat(path)
                except OSError:
                    continue
                digest.update(f"{path[skip:]}\0{status.st_size}\0{status.st_mtime_ns}\n"
                              .encode())
    return f"{__version__}+{digest.hexdigest()[:16]}"


@functools.cache
def module_stamp(name: str) -> str:
    """Where a module is installed, with its file's size and modification time (ns), or
    "none" when it is not installed.

    Stands for the module's version in cache keys: an upgrade rewrites the file. Cheaper
    than `importlib.metadata` (about 25 ms of imports) and does not import the module.
    """
    try:
        spec = importlib.util.find_spec(name)
    except (ImportError, ValueError):
        spec = None
    if spec is None or not spec.origin:
        return "none"
    try:
        status = os.stat(spec.origin)
    except OSError:
        return spec.origin
    return f"{spec.origin}:{status.st_size}:{status.st_mtime_ns}"
