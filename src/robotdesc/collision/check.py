"""`--check`: are the committed collision outputs current? A CI guard.

Stale means: a link's sources or the parameters changed (its key differs from the
manifest's), a link is new or gone, or a file the manifest lists is missing or was edited.
The check compares hashes rather than regenerating: outputs of native decomposition need not
be bit-identical across machines, but their inputs and parameters are.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

from robotdesc.collision.generate import Plan
from robotdesc.collision.manifest import read_manifest
from robotdesc.digest import file_digest


@dataclass(frozen=True)
class Staleness:
    """One reason the outputs are not current."""

    subject: str
    reason: str


def check_outputs(plan: Plan, out_dir: str, every_link: bool = True) -> list[Staleness]:
    """Everything that makes `out_dir` out of date for `plan` (empty: up to date).

    Args:
        every_link: the plan covers every link with geometry (no `--link` selection), so a
            manifest link outside it is gone; with a selection, other links are not judged.
    """
    manifest = read_manifest(out_dir)
    if manifest is None:
        return [Staleness(out_dir, "no robotdesc-collision.json manifest: outputs missing")]
    found = []
    planned = {}
    for sources, key in zip(plan.sources, plan.keys):
        planned[sources.link] = key
        entry = manifest.links.get(sources.link)
        if key is None:
            found.append(Staleness(sources.link, "a source mesh cannot be read"))
        elif entry is None:
            found.append(Staleness(sources.link, "no collision geometry generated"))
        elif entry.get("key") != key:
            found.append(Staleness(sources.link, "sources or parameters changed"))
    for link in manifest.links if every_link else ():
        if link not in planned:
            found.append(Staleness(link, "the link no longer has source geometry"))
    for name, digest in sorted(manifest.files.items()):
        current = file_digest(os.path.join(out_dir, name), follow_symlinks=False)
        if current is None:
            found.append(Staleness(name, "missing"))
        elif current != digest:
            found.append(Staleness(name, "edited since robotdesc wrote it"))
    return found
