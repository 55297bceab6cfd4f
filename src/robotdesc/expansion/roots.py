"""What the confined xacro worker may read, decided by the parent before it starts.

The data roots are the packages in use: the top file's package, every package folder the
resolver chain can return, and the folders of `--package-path` and of the config's
`packages`. A top file with no `package.xml` above it gets the entries of its own folder
except hidden ones (`.ssh`, `.aws`, `.git`), and never a home folder or `/` as a whole
(there, only the file itself). See docs/security.md, "Who decides the jail".
"""

from __future__ import annotations

import logging
import os
from dataclasses import dataclass
from pathlib import Path

from robotdesc.expansion.packages import PackageResolver, PackageResolverConfig
from robotdesc.expansion.result import ResolvedPackage
from robotdesc.expansion.sandbox import is_within
from robotdesc.trust import is_broad_folder

log = logging.getLogger(__name__)

#: The most entries of a package-less folder granted one by one; a folder with more gets
#: only the top file (a download folder is not a description package).
MAX_LOOSE_ENTRIES = 2000


@dataclass(frozen=True)
class Roots:
    """What the worker may read.

    Attributes:
        known: every package the resolver chain can return, in chain order.
        data: the folders (and files) the OS lets the worker read besides Python's code.
        guard: the roots the audit guard allows from the start (packages found later by
            `$(find)` are added to it as they are used).
    """

    known: tuple[ResolvedPackage, ...]
    data: tuple[str, ...]
    guard: tuple[str, ...]


def loose_file_roots(top: Path) -> tuple[str, ...]:
    """The roots of a top file that no package encloses: its folder's visible entries.

    Hidden entries and symlinks out of the folder are left out; in a home folder, `/` or a
    folder of more than `MAX_LOOSE_ENTRIES` entries only the top file is granted.
    """
    folder = top.parent
    real_top, real_folder = os.path.realpath(top), os.path.realpath(folder)
    if is_broad_folder(str(folder)):
        log.info("%s has no package.xml above it and lies in %s: the xacro worker may read "
                 "only this file", top, folder)
        return (real_top,)
    try:
        with os.scandir(folder) as entries:
            names = sorted(entry.name for entry in entries if not entry.name.startswith(".")
                           and (not entry.is_symlink() or is_within(entry.path, (real_folder,))))
    except OSError as exc:
        log.info("cannot list %s (%s): the xacro worker may read only %s", folder, exc, top)
        return (real_top,)
    if len(names) > MAX_LOOSE_ENTRIES:
        log.info("%s holds %d entries and no package.xml: the xacro worker may read only %s",
                 folder, len(names), top)
        return (real_top,)
    granted = [os.path.realpath(folder / name) for name in names]
    log.info("%s has no package.xml above it: the xacro worker may read the %d visible "
             "entries of %s (hidden ones left out)", top, len(granted), folder)
    return tuple(dict.fromkeys([real_top, *granted]))


def worker_roots(path: Path, resolver: PackageResolverConfig) -> Roots:
    """Resolve the whole package chain now (in the parent) and derive the readable roots.

    Never a whole workspace, home folder or `/`: see the module's docstring.
    """
    chain = PackageResolver(resolver)
    known = chain.candidates()
    top = (str(chain.enclosing[1]),) if chain.enclosing else loose_file_roots(path.absolute())
    explicit = []
    for folder in resolver.package_paths:
        inside = [p.path for p in known
                  if p.source == "--package-path" and is_within(p.path, (folder,))]
        explicit.extend(inside or [folder])
    mapped = [folder for _, folder in resolver.package_map]
    data = _real([*top, *explicit, *mapped, *(p.path for p in known)])
    return Roots(known, data, _real([*top, *explicit]))


def _real(folders: list[str]) -> tuple[str, ...]:
    """Real paths, in order, without repeats (what `is_within` compares against)."""
    return tuple(dict.fromkeys(os.path.realpath(folder) for folder in folders))
