"""The manifest robotdesc keeps beside its outputs: what it wrote (with hashes), from which
sources and parameters. It makes three promises checkable: never overwrite a file robotdesc
did not write, remove only its own stale files, and tell CI whether outputs are current."""

from __future__ import annotations

import hashlib
import json
import os
from dataclasses import dataclass, field

MANIFEST_NAME = "robotdesc-collision.json"
MANIFEST_FORMAT = 1


@dataclass(frozen=True)
class Manifest:
    """Attributes:
        files: relative path -> SHA-256 of every file robotdesc wrote in the folder.
        links: link -> {"key": sources+parameters hash, "files": [...], "status": ...}.
        source: the description the outputs were made from (relative to the folder).
        parameters: the options used.
    """

    files: dict = field(default_factory=dict)
    links: dict = field(default_factory=dict)
    source: str = ""
    parameters: dict = field(default_factory=dict)

    def to_json(self) -> bytes:
        data = {"format": MANIFEST_FORMAT, "tool": "robotdesc collision", "source": self.source,
                "parameters": self.parameters, "links": self.links, "files": self.files}
        return (json.dumps(data, indent=2, sort_keys=True) + "\n").encode()


def read_manifest(folder: str) -> Manifest | None:
    """The folder's manifest, or None when there is none (or it is unreadable)."""
    try:
        with open(os.path.join(folder, MANIFEST_NAME), encoding="utf-8") as stream:
            data = json.load(stream)
        return Manifest(dict(data["files"]), dict(data["links"]), str(data.get("source", "")),
                        dict(data.get("parameters", {})))
    except (OSError, ValueError, KeyError, TypeError):
        return None


def sha256_bytes(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def sha256_file(path: str) -> str | None:
    try:
        with open(path, "rb") as stream:
            return sha256_bytes(stream.read())
    except OSError:
        return None
