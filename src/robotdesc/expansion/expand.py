"""`expand_file`, the one entry point of the expansion (re-exported by `robotdesc.expansion`).

Xacro runs in an isolated worker process (see `robotdesc.expansion.worker`); results are
cached by the content of every file read.
"""

from __future__ import annotations

import dataclasses
import difflib
import logging
import os
import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Mapping

from robotdesc import errors
from robotdesc.cache_dir import cache_folder
from robotdesc.digest import bytes_digest
from robotdesc.expansion import cache
from robotdesc.expansion.answer import check_expanded, max_chain
from robotdesc.expansion.packages import PackageResolverConfig
from robotdesc.expansion.result import Expanded, ExpansionNote
from robotdesc.expansion.roots import worker_roots
from robotdesc.source import Span

log = logging.getLogger(__name__)

#: Environment variables a xacro file may read in safe mode (extend with ExpandOptions.env_allowlist).
DEFAULT_ENV_ALLOWLIST = ("ROS_DISTRO", "ROS_VERSION", "ROS_PYTHON_VERSION")
#: Largest plain URDF read (bytes).
MAX_URDF_BYTES = 256 * 1024 * 1024


@dataclass(frozen=True)
class ExpandOptions:
    """How to expand.

    Attributes:
        package_paths: folders holding packages (or a package), searched first.
        package_map: explicit (package name, folder) pairs (from config).
        trusted: lift the sandbox (full environment, any file, no audit guard) for own files.
        timeout_s: wall-clock limit of the worker (s).
        memory_mb: memory limit of the worker (MiB).
        max_macro_depth: nested macro calls allowed before the expansion is stopped.
        env_allowlist: environment variables visible to `$(env)`/`$(optenv)` in safe mode,
            in addition to DEFAULT_ENV_ALLOWLIST.
        use_cache: the one cache switch of a run (`--no-cache` sets it False): the
            expansion, mesh, rule and collision caches read and write nothing when off.
        cache_dir: the cache root (default: robotdesc.cache_dir.default_cache_dir()).
        unchecked_args: argument names not reported when no `<xacro:arg>` declares them
            (the config's default arguments, which apply to every target).
        substitutions_in_urdf: run a file that xacro's name test would pass through (no
            `.xacro` in its name, no `<xacro:` tag) through xacro when it holds `${...}` or
            `$(...)` substitutions, as the xacro command does with every file it is given
            (`robotdesc expand`). Off for the lint, which reads such a file as a URDF
            consumer would and reports the leftover substitutions (X201).
    """

    package_paths: tuple[str, ...] = ()
    package_map: tuple[tuple[str, str], ...] = ()
    trusted: bool = False
    timeout_s: float = 60.0
    memory_mb: int = 2048
    max_macro_depth: int = 2000
    env_allowlist: tuple[str, ...] = ()
    use_cache: bool = True
    cache_dir: str | None = None
    unchecked_args: tuple[str, ...] = ()
    substitutions_in_urdf: bool = False


def is_xacro(path: Path, head: bytes) -> bool:
    """True when the file needs xacro: a .xacro name or xacro tags in its text."""
    return ".xacro" in path.name or b"<xacro:" in head


_SUBSTITUTION = re.compile(rb"\$\{[^}]*\}|\$\([a-z]+[^)]*\)")


def holds_substitutions(data: bytes) -> bool:
    """True when the text holds a xacro `${...}` expression or `$(...)` substitution."""
    return _SUBSTITUTION.search(data) is not None


_UNICODE_BOMS = (b"\xef\xbb\xbf", b"\xff\xfe", b"\xfe\xff")


# C0 control bytes that XML 1.0 forbids anywhere in a document (tab, newline and carriage
# return are allowed): text a description is written in never holds them, binary data does.
_FORBIDDEN_CONTROLS = bytes([*range(0x00, 0x09), 0x0B, 0x0C, *range(0x0E, 0x20)])


def looks_binary(data: bytes) -> bool:
    """True for data that is no text a description could be written in (an STL, an image)."""
    head = data[:8192]
    if head.startswith(_UNICODE_BOMS[1:]):  # UTF-16 XML has NUL bytes but is text
        return False
    return len(head.translate(None, _FORBIDDEN_CONTROLS)) != len(head)


def _read_checked(path: Path) -> bytes:
    if not path.exists():
        raise errors.InputError("no such file", Span(str(path)))
    if not path.is_file():
        raise errors.InputError("not a regular file", Span(str(path)))
    if path.stat().st_size > MAX_URDF_BYTES:
        raise errors.LimitExceeded(f"file larger than {MAX_URDF_BYTES} bytes", Span(str(path)))
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise errors.InputError(f"cannot read: {exc.strerror}", Span(str(path))) from exc
    if looks_binary(data):
        kind = f" ({path.suffix})" if path.suffix else ""
        raise errors.InputError(f"binary data{kind}, not a URDF or xacro description",
                                Span(str(path)))
    return data


def expand_file(path: str | Path, args: Mapping[str, str] | None = None, *,
                options: ExpandOptions | None = None,
                while_expanding: Callable[[], object] | None = None) -> Expanded:
    """Expand a .xacro (in the worker) or read a plain .urdf.

    Args:
        path: the top-level description.
        args: xacro arguments (`name:=value` on the command line).
        options: resolution, sandbox, limits and cache settings.
        while_expanding: called once the worker has its job (not on a cache hit or for a
            plain URDF), in this thread, while the worker expands: this process has nothing
            else to do until its answer.

    Returns:
        The expanded document with provenance (see `Expanded`).

    Raises:
        InputError: the file cannot be expanded; its subclasses say why and where
            (UsageError: an argument that is not text).
    """
    options = options or ExpandOptions()
    args = dict(args or {})
    for name, value in args.items():
        if not isinstance(name, str) or not isinstance(value, str):
            text = str(value).lower() if isinstance(value, bool) else str(value)
            raise errors.UsageError(f"xacro argument {name!r} must be a string, not "
                                    f"{type(value).__name__} (xacro arguments are text: "
                                    f"{text!r})")
    path = Path(path).absolute()
    data = _read_checked(path)
    if not is_xacro(path, data):
        if not (options.substitutions_in_urdf and holds_substitutions(data)):
            return Expanded(source=str(path), xml=data, files=(), files_read=(str(path),))
        log.warning("%s: not named .xacro but holds xacro substitutions; expanded with xacro, "
                    "as the xacro command does (a URDF reader would see them as text)", path)
    resolver = PackageResolverConfig.from_environment(str(path), options.package_paths,
                                                      options.package_map)
    names = DEFAULT_ENV_ALLOWLIST + options.env_allowlist
    env = dict(os.environ) if options.trusted else {n: os.environ[n] for n in names if n in os.environ}
    cache_root = cache_folder(options.use_cache, options.cache_dir)
    key = None
    if cache_root is not None:
        key = cache.cache_key({"file": str(path), "digest": bytes_digest(data),
                               "args": sorted(args.items()),
                               "resolver": resolver.__dict__, "trusted": options.trusted,
                               "env": sorted(env.items()),
                               "max_macro_depth": options.max_macro_depth})
        hit = _checked(cache.load(cache_root, key, str(path)), path, resolver, options)
        if hit is not None:
            log.debug("expansion cache hit for %s", path)
            _log_packages(hit)
            return _with_notes(hit, args, options)
    # the worker's runner (subprocess, the OS confinement) only when the cache misses
    from robotdesc.expansion.runner import WorkerLimits, run_worker

    limits = WorkerLimits(options.timeout_s, options.memory_mb, options.max_macro_depth)
    unpassed = () if options.trusted else tuple(n for n in os.environ if n not in env)
    expanded = run_worker(path, args, resolver, trusted=options.trusted, env=env, limits=limits,
                          env_names=unpassed, while_waiting=while_expanding)
    _log_packages(expanded)
    if key is not None and cache_root is not None:
        cache.store(cache_root, key, expanded)
    return _with_notes(expanded, args, options)


def _checked(hit: Expanded | None, path: Path, resolver: PackageResolverConfig,
             options: ExpandOptions) -> Expanded | None:
    """A cache hit whose every path the parent can justify for this run (else a miss)."""
    if hit is None or options.trusted:
        return hit
    try:
        check_expanded(hit, worker_roots(path, resolver), path,
                       max_chain(options.max_macro_depth))
    except errors.InputError as exc:
        log.debug("expansion cache: entry for %s not used: %s", path, exc)
        return None
    return hit


def _with_notes(expanded: Expanded, args: Mapping[str, str], options: ExpandOptions) -> Expanded:
    """Attach what this run should say about its inputs, and say it on stderr (logged)."""
    notes: list[ExpansionNote] = []
    seen = set()
    for used in expanded.env_defaults:
        if options.trusted or used.name not in os.environ or (used.name, used.span) in seen:
            continue
        seen.add((used.name, used.span))
        notes.append(ExpansionNote(
            "env-not-passed", used.name,
            f"{used.name} is set in your environment but was not passed; the default "
            f"'{used.default}' was used; add --env {used.name}", used.span))
    declared = dict(reversed(expanded.declared_args))  # the first declaration wins
    for name in sorted(args):
        if name in declared or name in expanded.read_args or name in options.unchecked_args:
            continue
        known = [*declared, *(read for read in expanded.read_args if read not in declared)]
        close = difflib.get_close_matches(name, known, 1)
        hint = f"; did you mean '{close[0]}'?" if close else (
            "; the description declares no arguments" if not known else "")
        notes.append(ExpansionNote(
            "unknown-argument", name,
            f"xacro argument '{name}' is not declared by any <xacro:arg> nor read by $(arg)"
            f"{hint}", declared.get(close[0], Span(expanded.source, 1)) if close
            else Span(expanded.source, 1)))
    for note in notes:
        log.warning("%s: %s", note.span, note.message)
    return dataclasses.replace(expanded, notes=tuple(notes)) if notes else expanded


def _log_packages(expanded: Expanded) -> None:
    for package in expanded.packages:
        log.info("package %s -> %s (found via %s)", package.name, package.path, package.source)
