"""Command-line xacro arguments checked before any expansion: the arguments a description
declares (`<xacro:arg>`) or reads (`$(arg name)`), found by reading the file and the includes
that can be followed without expanding (relative paths, `$(find pkg)` of a known package).
A name none of them declares is a usage error at once (exit 2), with the closest declared
name; when an include cannot be followed the expansion decides (it notes unknown arguments).
"""

from __future__ import annotations

import difflib
import os
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from robotdesc.cache_dir import read_regular_file
from robotdesc.errors import InputError, UsageError
from robotdesc.linting.targets import (
    LintTarget,
    include_path,
    read_roots,
    target_name,
    xacro_name,
)
from robotdesc.trust import real_within
from robotdesc.xml_input import MAX_XML_FILE_BYTES, parse_xml

#: `$(arg name)` or `xacro.arg('name')` anywhere in a file's text.
_ARG_READ = re.compile(rb"\$\(arg\s+([A-Za-z0-9_\-]+)\s*\)"
                       rb"|xacro\.arg\(\s*[\"']([A-Za-z0-9_\-]+)[\"']\s*\)")
#: Files followed at most, per description.
_MAX_FILES = 500


@dataclass(frozen=True)
class DeclaredArguments:
    """The xacro arguments of a description, as far as reading (not expanding) tells.

    Attributes:
        names: declared by `<xacro:arg>` or read by `$(arg ...)`, in order of appearance.
        complete: every include was followed (else an argument may be declared in one
            that could not be: only the expansion can tell).
        xacro: the description uses xacro at all (a plain URDF takes no arguments).
    """

    names: tuple[str, ...]
    complete: bool
    xacro: bool


def declared_arguments(path: str, packages: Mapping[str, str] | None = None
                       ) -> DeclaredArguments:
    """The arguments `path` and the files it includes declare or read.

    Args:
        path: a description file.
        packages: package name -> folder, for `$(find pkg)` in include filenames (the
            including file's own package is found by itself).
    """
    names: list[str] = []
    top = os.path.abspath(path)
    roots = read_roots(top, packages or {})
    todo, seen = [top], set()
    complete, xacro = True, path.endswith(".xacro")
    while todo:
        file = todo.pop()
        real = os.path.realpath(file)
        if real in seen:
            continue
        seen.add(real)
        if len(seen) > _MAX_FILES:
            return DeclaredArguments(tuple(dict.fromkeys(names)), False, True)
        data = read_regular_file(file, MAX_XML_FILE_BYTES) if real_within(file, roots) else None
        try:
            root = parse_xml(data, file) if data is not None else None
        except InputError:  # the lint says what is wrong with it
            root = None
        if data is None or root is None:
            complete = False
            continue
        names += [(read or called).decode("utf-8") for read, called in _ARG_READ.findall(data)]
        xacro = xacro or b"$(arg" in data
        for element in root.iter():
            if not isinstance(element.tag, str):
                continue
            name, is_xacro = xacro_name(element)
            xacro = xacro or is_xacro
            if is_xacro and name == "arg" and element.get("name"):
                names.append(str(element.get("name")))
            elif is_xacro and name == "include":
                included = include_path(element.get("filename") or "", file,
                                        dict(packages or {}))
                if included is None:
                    complete = False
                else:
                    todo.append(included)
    return DeclaredArguments(tuple(dict.fromkeys(names)), complete, xacro)


def check_cli_arguments(targets: Sequence[LintTarget], args: Mapping[str, str]) -> None:
    """Refuse command-line arguments that no target can take, before any lint.

    An argument is refused when every target was read completely and none declares or
    reads it; a target that is a plain URDF takes none.

    Raises:
        UsageError: naming the argument, the closest declared name and the declared ones.
    """
    if not args or not targets:
        return
    found = {t.path: declared_arguments(t.path, dict(t.config.packages)) for t in targets}
    if not all(f.complete for f in found.values()):
        return
    declared = list(dict.fromkeys(n for f in found.values() for n in f.names))
    files = list(dict.fromkeys(target_name(t.path) for t in targets))
    one = len(files) == 1
    shown = files[0] if one else f"the {len(files)} descriptions"
    if not any(f.xacro for f in found.values()):
        given = " ".join(f"{name}:={value}" for name, value in args.items())
        raise UsageError(f"{shown} {'is a plain URDF' if one else 'are plain URDFs'}: "
                         f"no xacro arguments apply (given: {given})")
    for name in args:
        if name in declared:
            continue
        close = difflib.get_close_matches(name, declared, 1)
        hint = f"; did you mean '{close[0]}'?" if close else ""
        listing = (f" {'It' if one else 'They'} declare{'s' if one else ''}: "
                   f"{', '.join(declared)}." if declared else " No argument is declared.")
        raise UsageError(f"xacro argument '{name}' is not declared by {shown} nor any file "
                         f"{'it includes' if one else 'they include'}{hint}{listing}")


def one_run_per_file(targets: Sequence[LintTarget]) -> tuple[list[LintTarget], list[str]]:
    """Command-line arguments replace a file's config variants: one target per file (its
    config, no variant arguments) where the config made several; (targets, the files whose
    variants were replaced)."""
    counts: dict[str, int] = {}
    for target in targets:
        counts[target.path] = counts.get(target.path, 0) + 1
    kept: dict[str, LintTarget] = {}
    for target in targets:
        if target.path not in kept:
            kept[target.path] = target if counts[target.path] == 1 else \
                LintTarget(target.path, target.config)
    return list(kept.values()), [path for path, n in counts.items() if n > 1]
