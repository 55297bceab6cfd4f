"""Which paths the unconfined parent may read on a description's behalf.

Everything robotdesc reads comes from a tree someone else may have written (a pull request
that CI lints): a symlink in it can point at `~/.ssh`, a config in it can name the home
folder. These predicates are the one place that decides, by real path, whether a path stays
inside a tree, and which folders are never granted as a whole (see docs/security.md).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable


def real_within(path: str, roots: Iterable[str],
                real_path: Callable[[str], str] = os.path.realpath) -> bool:
    """True when the real path of `path` lies inside one of the (real) `roots`.

    A path whose real path cannot be found (a `/proc/1/cwd` link the kernel will not
    resolve for this process, a name too long) is not within anything: never an error.
    `real_path`: how to find it (`RealPaths`, for many paths at once).
    """
    try:
        real = real_path(path)
    except (OSError, ValueError):
        return False
    return any(real == root or real.startswith(root.rstrip(os.sep) + os.sep) for root in roots)


class RealPaths:
    """`os.path.realpath` for many paths at one moment, each folder resolved once (a
    description's files share a few folders; realpath looks at every component of every
    path): the folder's real path, joined with the last component unless that one is a
    symlink, which is resolved whole. Paths whose last component is empty, "." or ".."
    are resolved whole too. Use one for one check, then drop it: a folder's real path is
    not looked at again."""

    def __init__(self) -> None:
        self._folders: dict[str, str] = {}

    def __call__(self, path: str) -> str:
        folder, name = os.path.split(path)
        if not folder or name in ("", ".", ".."):
            return os.path.realpath(path)
        real_folder = self._folders.get(folder)
        if real_folder is None:
            real_folder = self._folders[folder] = os.path.realpath(folder)
        joined = os.path.join(real_folder, name)
        return os.path.realpath(joined) if os.path.islink(joined) else joined


def _homes() -> set[str]:
    """The real paths of home folders: the user's, `/root` and `/home` themselves."""
    homes = {"/root", "/home"}
    for candidate in (os.environ.get("HOME", ""), os.path.expanduser("~")):
        if candidate:
            homes.add(os.path.realpath(candidate))
    return homes


def is_broad_folder(folder: str) -> bool:
    """True for `/`, a home folder (the user's, `/root`, `/home/NAME`) or `/home`: folders
    never granted as a whole, whoever asks."""
    real = os.path.realpath(folder)
    return real == os.path.dirname(real) or real in _homes() \
        or os.path.dirname(real) == "/home"


def leaves_tree(path: str, tree: str) -> bool:
    """True when `path` is a symlink (or passes through one) whose real path leaves `tree`."""
    return not real_within(path, (os.path.realpath(tree),))
