"""Command-line paths -> the descriptions to lint, each with its config and matrix variant.

A file named on the command line is linted as given. A directory (a package or a whole
workspace) is searched for top-level descriptions: `*.urdf` files, and `*.xacro` /
`*.urdf.xacro` files whose `<robot>` root makes a robot rather than merely defining macros
for others to include. When the config that governs a file lists `targets`, those targets
(with their argument matrices) replace discovery for the files that config governs.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Iterable, Literal

from robotdesc.config import Config, discover_config, find_config_file, load_config
from robotdesc.errors import InputError
from robotdesc.linting.matrix import Variant, matrix_variants, variant_label
from robotdesc.source import Span

#: Files a directory walk looks at (".urdf.xacro" ends with ".xacro").
DESCRIPTION_SUFFIXES = (".urdf", ".xacro")
_SKIPPED_DIRS = {"build", "install", "log", "node_modules", "__pycache__"}
#: Xacro directives that do not by themselves make a robot at the top level of a file.
_DIRECTIVES = {"macro", "property", "include", "arg", "if", "unless"}
_XACRO_URIS = {"http://www.ros.org/wiki/xacro", "http://ros.org/wiki/xacro",
               "http://wiki.ros.org/xacro", "http://www.ros.org/xacro"}

Kind = Literal["robot", "library", "other"]


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
    """

    path: str
    directory: bool
    targets: tuple[LintTarget, ...]
    libraries: tuple[str, ...] = ()
    unlisted: tuple[str, ...] = ()


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
        specs = _specs_for(configs.for_file(absolute), absolute)
        return Discovery(path, False, tuple(_expand(absolute, configs.for_file(absolute),
                                                    specs)))
    robots, libraries = [], []
    for candidate in sorted(_walk(path)):
        (robots if description_kind(candidate) == "robot" else libraries).append(candidate)
    listed = _listed_files(path, [*robots, *libraries], configs)
    targets, unlisted = [], []
    for file in sorted(set(robots) | set(listed)):
        settings = configs.for_file(file)
        specs = _specs_for(settings, file)
        if settings.targets and not specs:
            unlisted.append(file)
            continue
        targets.extend(_expand(file, settings, specs))
    if not targets and not unlisted:
        raise InputError("no robot description (*.urdf, or *.xacro with a robot that is not "
                         "only macros) under this directory", Span(path))
    skipped = tuple(f for f in libraries if f not in set(listed))
    return Discovery(path, True, tuple(dict.fromkeys(targets)), skipped, tuple(unlisted))


def description_kind(path: str) -> Kind:
    """Whether a file is a top-level robot, a macro library, or no robot description.

    A `.urdf` with a `<robot>` root is a robot. A xacro file is a robot when its top level
    (looking inside `xacro:if`/`xacro:unless`) has a `<link>` or `<joint>`, calls a macro,
    or includes other files without defining macros itself; otherwise it only defines
    macros, properties or materials for others and is a library. A file that is not
    well-formed XML counts as a robot, so that linting it reports the syntax error.
    """
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                             remove_comments=True, remove_pis=True)
    try:
        root = etree.parse(path, parser).getroot()
    except (etree.XMLSyntaxError, OSError, ValueError):
        return "robot"
    if etree.QName(root).localname != "robot":
        return "other"
    if not path.endswith(".xacro"):
        return "robot"
    calls, links, includes, macros = False, False, False, False
    for element in _top_level(root):
        name, is_xacro = _xacro_name(element)
        if not is_xacro:
            links = links or name in ("link", "joint")
        elif name == "macro":
            macros = True
        elif name == "include":
            includes = True
        elif name not in _DIRECTIVES:
            calls = True
    return "robot" if links or calls or (includes and not macros) else "library"


# --- helpers ------------------------------------------------------------------------------


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
            self._loaded[found] = load_config(found)
        return self._loaded[found]

    def seen(self) -> list[Config]:
        return [self.explicit] if self.explicit is not None else list(self._loaded.values())


def _specs_for(config: Config, file: str) -> list:
    real = os.path.realpath(file)
    return [spec for spec in config.targets if os.path.realpath(spec.file) == real]


def _expand(file: str, config: Config, specs: list) -> list[LintTarget]:
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


def _walk(root: str) -> Iterable[str]:
    for directory, subdirs, files in os.walk(root):
        subdirs[:] = sorted(d for d in subdirs
                            if not d.startswith(".") and d not in _SKIPPED_DIRS)
        for name in files:
            if name.endswith(DESCRIPTION_SUFFIXES):
                yield os.path.abspath(os.path.join(directory, name))


def _top_level(root) -> Iterable:
    """The root's element children, looking through xacro:if / xacro:unless blocks."""
    for element in root:
        if not isinstance(element.tag, str):
            continue
        name, is_xacro = _xacro_name(element)
        if is_xacro and name in ("if", "unless"):
            yield from _top_level(element)
        else:
            yield element


def _xacro_name(element) -> tuple[str, bool]:
    """(local name, whether it is a xacro element) of an element."""
    from lxml import etree

    qname = etree.QName(element)
    is_xacro = qname.namespace in _XACRO_URIS or element.prefix == "xacro"
    return qname.localname, is_xacro
