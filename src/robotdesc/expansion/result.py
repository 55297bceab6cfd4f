"""The result of expanding a description: URDF text plus what the expansion learned."""

from __future__ import annotations

from dataclasses import dataclass

from robotdesc.rules.registry import MacroRecursion


@dataclass(frozen=True)
class ResolvedPackage:
    """A ROS package found by the resolver chain.

    Attributes:
        name: the package name (from package.xml `<name>`).
        path: its root directory (absolute).
        source: which resolver found it ("--package-path", "config", "enclosing",
            "workspace", "ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH").
    """

    name: str
    path: str
    source: str


@dataclass(frozen=True)
class Expanded:
    """An expanded description.

    Attributes:
        source: the top-level file (absolute path).
        xml: the URDF document (UTF-8). Elements carry the private provenance attribute
            (`robotdesc.source.PROVENANCE_ATTR`) when `files` is not empty.
        files: the file table the provenance attribute indexes.
        files_read: every file the expansion read (includes, YAML), absolute paths.
        packages: the packages resolved on the way.
        macro_recursion: the deepest self-recursion of each recursive macro.
        from_xacro: True when xacro ran (False for a plain URDF read as is).
        args: the xacro arguments used.
    """

    source: str
    xml: bytes
    files: tuple[str, ...] = ()
    files_read: tuple[str, ...] = ()
    packages: tuple[ResolvedPackage, ...] = ()
    macro_recursion: tuple[MacroRecursion, ...] = ()
    from_xacro: bool = False
    args: tuple[tuple[str, str], ...] = ()
