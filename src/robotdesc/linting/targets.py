"""Command-line paths -> the descriptions to lint, each with its config and matrix variant.

A file named on the command line is linted as given. A directory (a package or a whole
workspace) is searched for top-level descriptions: `*.urdf` files, and `*.xacro` /
`*.urdf.xacro` files (or `.urdf` files written in xacro) whose `<robot>` root makes a robot
rather than merely defining macros or properties for others to include. A file that another
robot found there includes is a fragment of that robot, not a robot of its own (it is linted
through its includer). An empty `<robot/>` placeholder is skipped with a note. When the
config that governs a file lists `targets`, those targets (with their argument matrices)
replace discovery for the files that config governs.

The packages under a searched directory are passed to each of its targets (as config
package entries), so that `$(find pkg)` and `package://pkg` resolve to them even when the
directory has no workspace markers (.git, src/, colcon files).
"""

from __future__ import annotations

import dataclasses
import fnmatch
import functools
import glob
import logging
import os
import re
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Literal, TypeAlias

from robotdesc.config import Config, TargetSpec, discover_config, find_config_file, load_config
from robotdesc.errors import InputError
from robotdesc.expansion.packages import crawl_packages, enclosing_package
from robotdesc.linting.matrix import Variant, matrix_variants, variant_label
from robotdesc.source import Span
from robotdesc.trust import leaves_tree, real_within

if TYPE_CHECKING:
    from lxml import etree

log = logging.getLogger(__name__)

#: Files a directory walk looks at (".urdf.xacro" ends with ".xacro").
DESCRIPTION_SUFFIXES = (".urdf", ".xacro")
_SKIPPED_DIRS = {"build", "install", "log", "node_modules", "__pycache__"}
#: Xacro directives that do not by themselves make a robot at the top level of a file.
_DIRECTIVES = {"macro", "property", "include", "arg", "if", "unless"}
_XACRO_URIS = {"http://www.ros.org/wiki/xacro", "http://ros.org/wiki/xacro",
               "http://wiki.ros.org/xacro", "http://www.ros.org/xacro"}
#: `$(find pkg)` at the start of an include's filename.
_FIND = re.compile(r"^\$\(find ([A-Za-z0-9_\-]+)\)")
#: A `${...}` or `$(...)` substitution inside an include's filename.
_SUBSTITUTION = re.compile(r"\$\{[^}]*\}|\$\([^)]*\)")
#: How deep includes are followed to decide whether a file makes a robot.
_MAX_INCLUDE_DEPTH = 8

Kind = Literal["robot", "library", "srdf", "other"]
#: Elements of MoveIt's semantic description (SRDF), whose root is a `<robot>` too.
_SRDF_ELEMENTS = {"group", "group_state", "disable_collisions", "enable_collisions",
                  "disable_default_collisions", "end_effector", "virtual_joint", "passive_joint",
                  "link_sphere_approximation", "joint_property"}


@dataclass(frozen=True)
class LintTarget:
    """One description to lint.

    Attributes:
        path: the file (absolute).
        config: the settings that apply to it.
        args: xacro arguments from the config target (its fixed args and the variant's);
            command-line arguments override them.
        variant: the matrix arguments that name this variant (empty: not a matrix target).
    """

    path: str
    config: Config = field(default_factory=Config)
    args: tuple[tuple[str, str], ...] = ()
    variant: Variant = ()

    def name(self, base: str | None = None) -> str:
        """The report name: the path relative to `base` (default: the working directory)
        plus the variant, e.g. ``urdf/ur.urdf.xacro[ur_type=ur5e]``."""
        return target_name(self.path, self.variant, base)


@dataclass(frozen=True)
class Discovery:
    """What one command-line path turned into.

    Attributes:
        path: the path as given.
        directory: whether it is a directory (then the lists below come from a search).
        targets: what to lint, in a stable order.
        libraries: files skipped as macro libraries (or not robots at all).
        unlisted: files skipped because their config lists `targets` without them.
        placeholders: files skipped because they are an empty `<robot/>`.
        fragments: files that would make a robot but that another robot found by the same
            search includes (e.g. a `*_common.urdf.xacro`), skipped: its includer is linted.
        packages: the (name, folder) pairs found under the directory and given to its
            targets.
        refused: description files that are symlinks whose real path leaves the searched
            directory: never read (a link to `~/.ssh/id_rsa` in a pull request), reported
            as inputs that could not be checked.
    """

    path: str
    directory: bool
    targets: tuple[LintTarget, ...]
    libraries: tuple[str, ...] = ()
    unlisted: tuple[str, ...] = ()
    placeholders: tuple[str, ...] = ()
    packages: tuple[tuple[str, str], ...] = ()
    fragments: tuple[str, ...] = ()
    refused: tuple[str, ...] = ()


def target_name(path: str, variant: Variant = (), base: str | None = None) -> str:
    """`path` relative to `base` (default: the working directory) when below it, else
    absolute, with "/" separators, followed by the variant label."""
    absolute = os.path.abspath(path)
    try:
        relative = os.path.relpath(absolute, base or os.getcwd())
    except ValueError:  # another drive (Windows)
        relative = absolute
    shown = absolute if relative.startswith("..") else relative
    return shown.replace(os.sep, "/") + variant_label(variant)


def discover_targets(path: str, config: Config | None = None) -> Discovery:
    """The targets one command-line path stands for.

    Args:
        path: a description file or a directory (package or workspace).
        config: settings that replace the discovered config of every file (`--config`).

    Raises:
        InputError: the path does not exist, a directory holds no description, or a config
            file is invalid.
    """
    if not os.path.exists(path):
        raise InputError("no such file or directory", Span(path))
    configs = _Configs(config)
    if not os.path.isdir(path):
        absolute = os.path.abspath(path)
        if path.endswith(DESCRIPTION_SUFFIXES + (".srdf",)) and is_srdf(absolute):
            raise InputError("this is an SRDF (a MoveIt semantic description: groups, "
                             "disabled collision pairs), not a URDF; lint the URDF it "
                             "describes", Span(path, 1))
        specs = _specs_for(configs.for_file(absolute), absolute)
        return Discovery(path, False, tuple(_expand(absolute, configs.for_file(absolute),
                                                    specs)))
    packages = _packages_under(path)
    robots, libraries, placeholders, semantic, refused = [], [], [], [], []
    for candidate in sorted(_walk(path)):
        if leaves_tree(candidate, path):
            refused.append(candidate)
            continue
        kind = "placeholder" if is_placeholder(candidate) else \
            description_kind(candidate, dict(packages))
        if kind == "placeholder":
            placeholders.append(candidate)
        elif kind == "robot":
            robots.append(candidate)
        elif kind == "srdf":
            semantic.append(candidate)
        else:
            libraries.append(candidate)
    if semantic:
        log.warning("note: skipped %d SRDF file(s), MoveIt semantic descriptions rather than "
                    "URDF: %s", len(semantic),
                    ", ".join(target_name(f, (), path) for f in semantic[:5])
                    + (f", ... ({len(semantic) - 5} more)" if len(semantic) > 5 else ""))
    fragments = included_by_others(robots, libraries, dict(packages))
    robots = [file for file in robots if file not in fragments]
    listed = _listed_files(path, [*robots, *libraries, *placeholders, *fragments], configs)
    targets, unlisted = [], []
    for file in sorted(set(robots) | set(listed)):
        settings = _with_packages(configs.for_file(file), packages, file)
        specs = _specs_for(settings, file)
        if settings.targets and not specs:
            unlisted.append(file)
            continue
        targets.extend(_expand(file, settings, specs))
    skipped_placeholders = tuple(f for f in placeholders if f not in set(listed))
    for file in skipped_placeholders:
        log.warning("note: skipped %s: an empty <robot/> placeholder, nothing to lint",
                    target_name(file, (), path))
    if not targets and not unlisted and not skipped_placeholders and not refused:
        only = f" (only {len(semantic)} SRDF file(s))" if semantic else ""
        raise InputError("no robot description (*.urdf, or *.xacro with a robot that is not "
                         f"only macros) under this directory{only}", Span(path))
    skipped = tuple(f for f in libraries if f not in set(listed))
    return Discovery(path, True, tuple(dict.fromkeys(targets)), skipped, tuple(unlisted),
                     skipped_placeholders, packages,
                     tuple(f for f in sorted(fragments) if f not in set(listed)), tuple(refused))


def included_by_others(robots: list[str], others: list[str],
                       packages: dict[str, str]) -> set[str]:
    """The files of `robots` that another description file of the search (a robot or a
    library in `others`) includes, with or without the xacro prefix: fragments of a robot,
    not robots.

    An include is followed as far as it can be without expanding: `$(find pkg)` from
    `packages`, and a name with `${...}`/`$(...)` in it as a pattern when a literal part of
    the name is left besides its extension (`${side}_arm.transmissions.urdf.xacro` matches
    both sides; `$(arg model).urdf.xacro` matches nothing). Fragments are those reached from
    a file nobody includes; files that only include each other are kept (no includer would
    be left to lint them).
    """
    files = list(dict.fromkeys([*robots, *others]))
    by_real = {os.path.realpath(file): file for file in files}
    includes: dict[str, set[str]] = {file: set() for file in files}
    for file in files:
        root = _read_root(file)
        if root is None:
            continue
        for element in root.iter():
            if isinstance(element.tag, str) and xacro_name(element)[0] == "include":
                pattern = _include_pattern(element.get("filename") or "", file, packages)
                if pattern is not None:
                    includes[file] |= {by_real[real] for real in fnmatch.filter(by_real, pattern)
                                       if by_real[real] != file}
    included = set().union(*includes.values())
    reached: set[str] = set()
    todo = [file for file in files if file not in included]
    while todo:
        for child in includes[todo.pop()] - reached:
            reached.add(child)
            todo.append(child)
    return reached & set(robots)


def _include_pattern(filename: str, including: str, packages: dict[str, str]) -> str | None:
    """The real path (an fnmatch pattern when the name holds substitutions) of the file an
    include names, or None when it cannot be told without expanding."""
    found = _without_find(filename, including, packages)
    if found is None:
        return None
    filename = found
    folder, name = os.path.split(filename)
    if not name or "$" in _SUBSTITUTION.sub("", filename) or _SUBSTITUTION.search(folder):
        return None
    pieces = _SUBSTITUTION.split(name)
    if len(pieces) > 1:
        literal = "".join(pieces)
        for suffix in (".xacro", ".urdf"):
            literal = literal.removesuffix(suffix)
        if not literal:
            return None
    folder = os.path.realpath(os.path.join(os.path.dirname(including), folder))
    return os.path.join(glob.escape(folder), "*".join(glob.escape(piece) for piece in pieces))


def is_placeholder(path: str) -> bool:
    """Whether a file is an intentionally empty `<robot/>` (comments aside): a placeholder
    that a folder lint skips with a note."""
    root = _read_root(path)
    return (root is not None and _local_name(root) == "robot"
            and not any(isinstance(child.tag, str) for child in root))


def description_kind(path: str, packages: dict[str, str] | None = None) -> Kind:
    """Whether a file is a top-level robot, a library, or no robot description.

    A `.urdf` with a `<robot>` root is a robot, unless it is written in xacro (it has xacro
    elements): then it is judged as a xacro file. A xacro file is a robot when its top
    level (looking inside `xacro:if`/`xacro:unless`) has a `<link>` or `<joint>`, calls a
    macro or has an `<include>` without the xacro prefix (old files; the lint says so), or
    when it includes, without defining macros itself, a file that makes something:
    includes are followed (relative paths, and `$(find pkg)` for the `packages` given,
    name -> folder); one that cannot be followed counts as making a robot. A file
    that only defines macros, properties, arguments or materials for others is a library.
    A file that is not well-formed XML counts as a robot, so that linting it reports the
    syntax error.
    """
    root = _read_root(path)
    if root is None:
        return "robot"
    if _local_name(root) != "robot":
        return "other"
    if is_srdf(path, root):
        return "srdf"
    if not path.endswith(".xacro") and not _uses_xacro(root):
        return "robot"
    makes = _makes_something(path, root, packages or {}, frozenset({os.path.realpath(path)}))
    return "robot" if makes else "library"


# --- helpers ------------------------------------------------------------------------------


#: An lxml element (lxml is imported when a file is read).
XmlElement: TypeAlias = "etree._Element"


def is_srdf(path: str, root: XmlElement | None = None) -> bool:
    """Whether a file is a MoveIt semantic description (SRDF, or its xacro): named
    `*.srdf[.xacro]`, or a `<robot>` whose top level holds SRDF elements and no link or joint."""
    if ".srdf" in os.path.basename(path).lower():
        return True
    if root is None and not _mentions_srdf_elements(path):
        return False  # without parsing (a warm lint of a file does not import lxml)
    root = _read_root(path) if root is None else root
    if root is None or _local_name(root) != "robot":
        return False
    names = {xacro_name(element) for element in _top_level(root)}
    return (any(name in _SRDF_ELEMENTS for name, is_xacro in names if not is_xacro)
            and not any(name in ("link", "joint") for name, is_xacro in names if not is_xacro))


def _mentions_srdf_elements(path: str) -> bool:
    """Whether the file's text holds the start tag of an SRDF element (or is unreadable):
    a file without any cannot be an SRDF."""
    try:
        with open(path, "rb") as stream:
            data = stream.read(MAX_SRDF_PROBE_BYTES)
    except OSError:
        return True
    return any(re.search(rb"<(?:[A-Za-z_][\w.\-]*:)?" + name.encode() + rb"[\s/>]", data)
               for name in _SRDF_ELEMENTS)


#: How much of a file `is_srdf` reads to look for SRDF elements before parsing it.
MAX_SRDF_PROBE_BYTES = 64 << 20


def _read_root(path: str) -> XmlElement | None:
    """The root element of an XML file, or None when it is not well-formed (or unreadable).

    A search asks for each file several times (placeholder, kind, includes of others): the
    parsed root is kept per file state (size and modification time), never served stale.
    """
    try:
        status = os.stat(path)
    except OSError:
        return None
    return _parsed_root(os.path.abspath(path), status.st_size, status.st_mtime_ns)


@functools.lru_cache(maxsize=4096)
def _parsed_root(path: str, size: int, mtime_ns: int) -> XmlElement | None:
    """`_read_root` for one state of the file (`size`, `mtime_ns` key the cache only)."""
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                             remove_comments=True, remove_pis=True)
    try:
        return etree.parse(path, parser).getroot()
    except (etree.XMLSyntaxError, OSError, ValueError):
        return None


def _local_name(element: XmlElement) -> str:
    from lxml import etree

    return str(etree.QName(element).localname)


def _uses_xacro(root: XmlElement) -> bool:
    """Whether a document holds xacro elements (a declared namespace alone is not use)."""
    return any(xacro_name(element)[1] for element in root.iter()
               if isinstance(element.tag, str))


def _makes_something(path: str, root: XmlElement, packages: dict[str, str], seen: frozenset[str],
                     depth: int = 0) -> bool:
    """Whether a xacro document, with what it includes, makes links, joints or macro calls.

    The defining part of a library (macros, properties, args, materials) makes nothing; an
    include makes something when the included file does, or when it cannot be followed.
    """
    includes, macros = [], False
    for element in _top_level(root):
        name, is_xacro = xacro_name(element)
        if not is_xacro:
            if name in ("link", "joint", "include"):
                return True  # an unprefixed <include> (NAO's): linting says what is wrong
        elif name == "macro":
            macros = True
        elif name == "include":
            includes.append(element.get("filename") or "")
        elif name not in _DIRECTIVES:
            return True  # a macro call
    if macros or not includes:
        return False
    for filename in includes:
        included = include_path(filename, path, packages)
        if included is None or depth >= _MAX_INCLUDE_DEPTH:
            return True  # cannot tell: assume it makes the robot
        real = os.path.realpath(included)
        if real in seen:
            continue
        if not real_within(included, read_roots(path, packages)):
            return True  # out of the packages (`../`, a symlink): not read, assumed a robot
        sub = _read_root(included)
        if sub is None or _makes_something(included, sub, packages, seen | {real}, depth + 1):
            return True
    return False


def read_roots(including: str, packages: Mapping[str, str]) -> tuple[str, ...]:
    """Where the parent may read a file `including` includes, without expanding: the
    including file's package (or folder) and `packages` (real paths); never a file a
    symlink or `../` leads out to."""
    found = enclosing_package(including)
    own = str(found[1]) if found else os.path.dirname(os.path.abspath(including))
    return tuple(os.path.realpath(folder) for folder in (own, *packages.values()))


def include_path(filename: str, including: str, packages: dict[str, str]) -> str | None:
    """The file an include names, when it can be known without expanding; else None."""
    found = _without_find(filename, including, packages)
    if found is None:
        return None
    filename = found
    if "$" in filename or not filename:
        return None
    resolved = os.path.join(os.path.dirname(including), filename)
    return resolved if os.path.isfile(resolved) else None


def _without_find(filename: str, including: str, packages: dict[str, str]) -> str | None:
    """`filename` with a leading `$(find pkg)` replaced by the package's folder (from
    `packages`, or the including file's own package); None when pkg is not known."""
    match = _FIND.match(filename)
    if not match:
        return filename
    folder = packages.get(match.group(1))
    if folder is None:
        found = enclosing_package(including)
        folder = str(found[1]) if found and found[0] == match.group(1) else None
    return None if folder is None else folder + filename[match.end():]


def _packages_under(directory: str) -> tuple[tuple[str, str], ...]:
    """The packages under a searched directory (and the directory itself), name -> folder."""
    found = crawl_packages(Path(os.path.abspath(directory)))
    return tuple(sorted((name, str(folder)) for name, folder in found.items()))


def _with_packages(config: Config, packages: tuple[tuple[str, str], ...], file: str) -> Config:
    """`config` with the searched directory's packages appended to its own.

    The config's own entries come first; the file's enclosing package is left to the
    resolver's own "enclosing" step (so that a same-named copy elsewhere cannot shadow it).
    """
    if not packages:
        return config
    enclosing = enclosing_package(file)
    own = {name for name, _ in config.packages}
    if enclosing:
        own.add(enclosing[0])
    extra = tuple((name, folder) for name, folder in packages if name not in own)
    return dataclasses.replace(config, packages=tuple(config.packages) + extra) if extra else config


class _Configs:
    """Config lookups for one discovery, each config file loaded once."""

    def __init__(self, explicit: Config | None) -> None:
        self.explicit = explicit
        self._loaded: dict[str, Config] = {}

    def for_file(self, path: str) -> Config:
        if self.explicit is not None:
            return self.explicit
        found = find_config_file(path)
        if found is None:
            return discover_config(path)
        if found not in self._loaded:
            self._loaded[found] = load_config(found, scanned=True)
        return self._loaded[found]

    def seen(self) -> list[Config]:
        return [self.explicit] if self.explicit is not None else list(self._loaded.values())


def _specs_for(config: Config, file: str) -> list[TargetSpec]:
    real = os.path.realpath(file)
    return [spec for spec in config.targets if os.path.realpath(spec.file) == real]


def _expand(file: str, config: Config, specs: list[TargetSpec]) -> list[LintTarget]:
    if not specs:
        return [LintTarget(file, config)]
    return [LintTarget(file, config, tuple(spec.args) + variant, variant)
            for spec in specs for variant in matrix_variants(spec.matrix)]


def _listed_files(directory: str, files: list[str], configs: _Configs) -> list[str]:
    """Config target files under `directory`, from the configs of `files` and of the
    directory itself."""
    for file in files:
        configs.for_file(file)
    configs.for_file(os.path.abspath(directory))  # find_config_file starts in a directory
    root = os.path.realpath(directory) + os.sep
    return sorted({spec.file for settings in configs.seen() for spec in settings.targets
                   if os.path.realpath(spec.file).startswith(root)})


def _walk(root: str) -> Iterator[str]:
    for directory, subdirs, files in os.walk(root):
        subdirs[:] = sorted(d for d in subdirs
                            if not d.startswith(".") and d not in _SKIPPED_DIRS)
        for name in files:
            if name.endswith(DESCRIPTION_SUFFIXES):
                yield os.path.abspath(os.path.join(directory, name))


def _top_level(root: XmlElement) -> Iterator[XmlElement]:
    """The root's element children, looking through xacro:if / xacro:unless blocks."""
    for element in root:
        if not isinstance(element.tag, str):
            continue
        name, is_xacro = xacro_name(element)
        if is_xacro and name in ("if", "unless"):
            yield from _top_level(element)
        else:
            yield element


def xacro_name(element: XmlElement) -> tuple[str, bool]:
    """(local name, whether it is a xacro element) of an element."""
    from lxml import etree

    qname = etree.QName(element)
    is_xacro = qname.namespace in _XACRO_URIS or element.prefix == "xacro"
    return qname.localname, is_xacro
