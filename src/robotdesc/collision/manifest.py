"""The manifest robotdesc keeps beside its outputs: what it wrote (with hashes), from which
sources and parameters. It makes three promises checkable: never overwrite a file robotdesc
did not write, remove only its own stale files, and tell CI whether outputs are current.

A manifest is data in a folder anyone may edit: an entry names a file robotdesc may touch
only when `own_file` accepts it (a name robotdesc writes, relative, inside the folder after
symlinks, a regular file). The manifest and the files are read without following a FIFO or
a device (they never hang a run)."""

from __future__ import annotations

import json
import os
import re
import stat
from dataclasses import dataclass, field

from robotdesc.cache_dir import read_regular_file

MANIFEST_NAME = "robotdesc-collision.json"
MANIFEST_FORMAT = 1
#: The largest manifest read.
MAX_MANIFEST_BYTES = 16 << 20
#: The names robotdesc writes in an output folder (see output.py), besides the manifest.
OWN_NAME = re.compile(r"meshes/[A-Za-z0-9_.-]+\.stl|[A-Za-z0-9_.-]+\.collision\.(urdf|xacro|patch)")


@dataclass(frozen=True)
class Manifest:
    """Attributes:
        files: relative path -> SHA-256 of every file robotdesc wrote in the folder.
        links: link -> {"key": sources+parameters hash, "status": ..., "method": ...}.
        source: the description the outputs were made from (relative to the folder).
        parameters: the options used.
    """

    files: dict[str, str] = field(default_factory=dict)
    links: dict[str, dict[str, str]] = field(default_factory=dict)
    source: str = ""
    parameters: dict[str, object] = field(default_factory=dict)

    def to_json(self) -> bytes:
        data = {"format": MANIFEST_FORMAT, "tool": "robotdesc collision", "source": self.source,
                "parameters": self.parameters, "links": self.links, "files": self.files}
        return (json.dumps(data, indent=2, sort_keys=True) + "\n").encode()


def read_manifest(folder: str) -> Manifest | None:
    """The folder's manifest, or None when there is none (or it is unreadable)."""
    raw = read_regular_file(os.path.join(folder, MANIFEST_NAME), MAX_MANIFEST_BYTES)
    if raw is None:
        return None
    try:
        data = json.loads(raw)
        return Manifest(dict(data["files"]), dict(data["links"]), str(data.get("source", "")),
                        dict(data.get("parameters", {})))
    except (ValueError, KeyError, TypeError, AttributeError):
        return None


def own_file(folder: str, name: object) -> str | None:
    """The path of manifest entry `name` in `folder` when robotdesc may have written it (so
    may read, replace or delete it), else None: the name must be one robotdesc writes
    (`OWN_NAME`: no `..`, no absolute path), lie inside the folder after symlinks, and be a
    regular file or absent."""
    if not isinstance(name, str) or not OWN_NAME.fullmatch(name) \
            or any(part in ("", ".", "..") for part in name.split("/")):
        return None
    root = os.path.realpath(folder)
    path = os.path.join(root, *name.split("/"))
    parent = os.path.realpath(os.path.dirname(path))
    if parent != root and os.path.commonpath([root, parent]) != root:
        return None
    try:
        info = os.lstat(path)
    except FileNotFoundError:
        return path
    except OSError:
        return None
    return path if stat.S_ISREG(info.st_mode) else None
