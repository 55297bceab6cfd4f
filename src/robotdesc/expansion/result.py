"""The result of expanding a description: URDF text plus what the expansion learned."""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any

from robotdesc.source import Span


@dataclass(frozen=True)
class MacroRecursion:
    """How deep one macro recursed during expansion.

    Attributes:
        macro: the macro's name.
        depth: the deepest nesting of the macro within itself.
        defined_at: where the macro is defined.
        called_at: the outermost call site of the deepest chain.
    """

    macro: str
    depth: int
    defined_at: Span
    called_at: Span | None = None


@dataclass(frozen=True)
class EnvDefault:
    """An `$(optenv NAME default)` that used its default because NAME was not passed.

    Attributes:
        name: the environment variable.
        default: the value used instead.
        span: where the lookup is written.
    """

    name: str
    default: str
    span: Span


@dataclass(frozen=True)
class ExpansionNote:
    """Something about the expansion's inputs the URDF does not show (rules report it).

    Attributes:
        kind: "env-not-passed" (a variable set in the caller's environment was not passed)
            or "unknown-argument" (a `name:=value` no `<xacro:arg>` declares).
        subject: the variable or argument name.
        message: what happened and what to do, in a user's words.
        span: where (the lookup, the closest declaration, or the top file).
    """

    kind: str
    subject: str
    message: str
    span: Span


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
        declared_args: every evaluated `<xacro:arg>`: (name, where it is declared).
        read_args: the names of passed arguments the expansion read (`$(arg name)`), declared
            or not: xacro lets a file read an argument it never declares.
        env_defaults: optenv lookups of variables that were not passed.
        notes: what the rules should report about the inputs (computed by the parent for
            this run, from the facts above and its own environment; never cached).
    """

    source: str
    xml: bytes
    files: tuple[str, ...] = ()
    files_read: tuple[str, ...] = ()
    packages: tuple[ResolvedPackage, ...] = ()
    macro_recursion: tuple[MacroRecursion, ...] = ()
    from_xacro: bool = False
    args: tuple[tuple[str, str], ...] = ()
    declared_args: tuple[tuple[str, Span], ...] = ()
    read_args: tuple[str, ...] = ()
    env_defaults: tuple[EnvDefault, ...] = ()
    notes: tuple[ExpansionNote, ...] = ()

    def __repr__(self) -> str:
        """A one-line summary (the URDF itself is `.xml`)."""
        args = " ".join(f"{name}:={value}" for name, value in self.args)
        args = args if len(args) <= 200 else args[:200] + "..."
        return (f"<Expanded {os.path.basename(self.source)!r}: {len(self.xml):,} bytes of URDF "
                f"from {len(self.files)} file(s), {len(self.packages)} package(s)"
                + (f", {args}" if args else "") + ">")


def decode_input_facts(data: dict[str, Any]) -> dict[str, Any]:
    """The `declared_args`, `read_args` and `env_defaults` of an `Expanded` encoded with
    `dataclasses.asdict` (for the expansion cache), as keyword arguments of `Expanded`."""
    return {"declared_args": tuple((name, Span(**span))
                                   for name, span in data.get("declared_args", ())),
            "read_args": tuple(data.get("read_args", ())),
            "env_defaults": tuple(EnvDefault(d["name"], d["default"], Span(**d["span"]))
                                  for d in data.get("env_defaults", ()))}
