"""The whole-result cache: a lint of unchanged inputs is a cache read.

One entry per target and variant, under a key made of robotdesc's code, the installed
backends, the target, its arguments and variant, the config, the rule selection and the
expansion settings (package paths, the allowed environment). The entry records the SHA-256 of
every file the lint read (the description, its includes, the config, every package.xml, every
mesh), computed by this process from the files themselves after the lint (never taken from the
expansion worker), and the findings. A hit prints the stored findings: nothing is expanded,
parsed or checked.

The cache folder may be shared (a CI cache restored on several branches) and written by
someone else, so an entry is evidence to check, never a verdict to take:
- it is read only as a regular file no larger than `MAX_ENTRY_BYTES` (`read_regular_file`),
  stored under the key asked for, and parsed against a strict schema (types, sizes, counts,
  no control characters in any text); anything else is a miss, never an error;
- it must list inputs, the target among them; each is re-hashed here, opened without following
  a symlink, and its path must be its own real path (no symlinked folder on the way); one
  input that differs, is missing or is not a regular file makes a miss;
- every span of a finding must point into one of those verified inputs, so an entry can never
  make robotdesc show text from another file;
- environment variables whose presence changed what the lint said must be as recorded.
An entry cannot prove that its findings are the ones robotdesc would compute: whoever may
write the cache folder may hide findings from a run that reads it (see docs/ci.md).

Nothing is stored when an input vanished or changed during the lint (its modification time
is after the lint began; on a file system with whole-second times, within 2 s of it), when a mesh does not resolve (a file that appears later would change
the findings), or for `--trusted` runs (they may read any file and the whole environment).
`--no-cache` and `ROBOTDESC_CACHE_DIR=off` turn the cache off.
"""

from __future__ import annotations

import functools
import hashlib
import json
import logging
import os
import re
import stat
import sys
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from robotdesc.code_stamp import FINDING_BACKENDS, code_id, module_stamp
from robotdesc.cache_dir import cache_folder, entry_file, read_entry, write_entry
from robotdesc.diagnostics import Diagnostic, Severity
from robotdesc.digest import FileStamp, file_digest, file_stamp
from robotdesc.expansion import DEFAULT_ENV_ALLOWLIST, ExpandOptions
from robotdesc.linting.result import LintResult
from robotdesc.output import RunInput, RunInputs
from robotdesc.source import PassedValue, Provenance, Span

log = logging.getLogger(__name__)

_FORMAT = 1
#: The largest entry read (findings of one target; the Engineer's are a few kB).
MAX_ENTRY_BYTES = 16 << 20
#: Limits of the schema (an entry beyond any of them is a miss).
MAX_INPUTS = 100_000
MAX_DIAGNOSTICS = 100_000
MAX_PATH = 4096
MAX_TEXT = 1 << 20  # a message, an element name, a fix
MAX_STACK = 100_000
MAX_COUNT = 10**9
#: Environment variables that decide package resolution (besides the explicit settings).
RESOLVER_ENV = ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH")
#: Slack for file systems whose modification times are whole seconds (ns).
_MTIME_SLACK_NS = 2_000_000_000

_CODE = re.compile(r"[A-Z]{1,4}[0-9]{1,4}")
_NAME = re.compile(r"[a-z0-9]+(-[a-z0-9]+)*")
_DIGEST = re.compile(r"[0-9a-f]{64}")
_ARG = re.compile(r"[A-Za-z0-9_\-]{1,200}")
#: C0 controls other than tab and newline, DEL and C1 controls: never in a stored text.
_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f]")


class _Invalid(ValueError):
    """An entry that does not match the schema."""


@dataclass(frozen=True)
class CacheKey:
    """Where one target's result is stored, and what it was computed with.

    Attributes:
        folder: the cache root.
        digest: the key (hex SHA-256 of everything besides file contents).
    """

    folder: Path
    digest: str

    @property
    def path(self) -> Path:
        """The entry's file."""
        return entry_file(self.folder / "results", self.digest)


def result_key(target: str, *, config: object, args: Mapping[str, str],
               variant: Sequence[tuple[str, str]], select: Sequence[str] | None,
               ignore: Sequence[str], expand_options: ExpandOptions | None) -> CacheKey | None:
    """The key of one target's lint, or None when the cache is off for it (`--no-cache`,
    `ROBOTDESC_CACHE_DIR=off`, `--trusted`)."""
    options = expand_options
    if options is not None and options.trusted:
        return None
    folder = cache_folder(options.use_cache, options.cache_dir) if options is not None \
        else cache_folder()
    if folder is None:
        return None
    allowed = _allowed_env(options)
    material = {
        "format": _FORMAT, "robotdesc": code_id(),
        "python": ".".join(map(str, sys.version_info[:3])),
        "backends": [module_stamp(name) for name in FINDING_BACKENDS],
        "target": os.path.abspath(target), "args": sorted(args.items()),
        "variant": [list(pair) for pair in variant], "config": repr(config),
        "select": None if select is None else list(select), "ignore": list(ignore),
        "package_paths": [os.path.abspath(p) for p in getattr(options, "package_paths", ())],
        "package_map": [list(p) for p in getattr(options, "package_map", ())],
        "max_macro_depth": getattr(options, "max_macro_depth", None),
        "env": sorted((name, os.environ[name]) for name in allowed if name in os.environ),
    }
    text = json.dumps(material, sort_keys=True, default=str)
    return CacheKey(folder, hashlib.sha256(text.encode()).hexdigest())


def _allowed_env(options: ExpandOptions | None) -> tuple[str, ...]:
    from_options = tuple(getattr(options, "env_allowlist", ()) or ())
    return tuple(sorted(set(DEFAULT_ENV_ALLOWLIST + from_options + RESOLVER_ENV)))


def load(key: CacheKey | None, target: str) -> LintResult | None:
    """The stored result of `target` under `key` when every recorded input is unchanged;
    None on any miss (absent, malformed, stale, or the cache is off)."""
    if key is None:
        return None
    raw = read_entry(key.path, MAX_ENTRY_BYTES)
    if raw is None:
        return None
    try:
        record = json.loads(raw)
        return _checked(record, key, os.path.abspath(target))
    except (ValueError, TypeError, KeyError, IndexError, AttributeError, RecursionError) as exc:
        log.debug("result cache: %s not used: %s", key.path, exc)
        return None


def _checked(record: Any, key: CacheKey, target: str) -> LintResult | None:
    """The result an entry records, after checking its shape and its inputs."""
    _expect(isinstance(record, dict) and record.get("format") == _FORMAT
            and record.get("key") == key.digest, "another format or key")
    inputs = record["inputs"]
    _expect(isinstance(inputs, list) and 0 < len(inputs) <= MAX_INPUTS, "no inputs")
    verified: set[str] = set()
    for item in inputs:
        _expect(isinstance(item, list) and len(item) == 2, "an input is not [path, digest]")
        path, digest = _path(item[0]), item[1]
        _expect(isinstance(digest, str) and _DIGEST.fullmatch(digest) is not None,
                "a digest is not SHA-256")
        verified.add(path)
    _expect(os.path.realpath(target) in verified, "the target is not among the inputs")
    env = record["env"]
    _expect(isinstance(env, dict) and len(env) <= 1000, "env is not a map")
    for name, present in env.items():
        _expect(isinstance(name, str) and _ARG.fullmatch(name) is not None
                and isinstance(present, bool), "env is not names -> presence")
    result = _decode_result(record["result"], verified, target)
    for name, present in env.items():  # cheap checks first, file contents last
        if (name in os.environ) != present:
            log.debug("result cache: %s is %s now", name, "set" if not present else "unset")
            return None
    for path, digest in inputs:
        if not _unchanged(path, digest):
            log.debug("result cache: %s changed", path)
            return None
    return result


def _unchanged(path: str, digest: str) -> bool:
    """Whether `path` is still a regular file, its own real path, with this content."""
    folder, name = os.path.split(path)
    if _real(folder) != folder or name in ("", ".", ".."):  # a symlink on the way
        return False
    return _digest(path) == digest


def _digest(path: str) -> str | None:
    """The content digest of a file that is no symlink. Remembered in this process under the
    file's identity (`digest.file_stamp`), so that variants sharing their includes and meshes
    hash each once per run, and an editor session hashes only what was saved since."""
    stamp = file_stamp(path)
    if stamp is None:
        return None
    identity = (path, *stamp)
    if identity not in _DIGESTS:
        if len(_DIGESTS) > 100_000:
            _DIGESTS.clear()
        _DIGESTS[identity] = file_digest(path, follow_symlinks=False)
    return _DIGESTS[identity]


def checked_digest(path: str) -> tuple[FileStamp, str] | None:
    """The identity and digest of `path` as this process last verified them (an entry's
    input, hashed by `load`), when the file still has that identity; else None."""
    stamp = file_stamp(path)
    if stamp is None:
        return None
    digest = _DIGESTS.get((path, *stamp))
    return None if digest is None else (stamp, digest)


#: (path, file identity) -> digest (None: unreadable), for this process.
_DIGESTS: dict[tuple[str, int, int, int, int, int], str | None] = {}


def new_run() -> None:
    """Start a run: folders are resolved again (a symlink may have been put in place)."""
    _real.cache_clear()


def _decode_result(data: Any, verified: set[str], target: str) -> LintResult:
    _expect(isinstance(data, dict), "result is not an object")
    diagnostics = data["diagnostics"]
    _expect(isinstance(diagnostics, list) and len(diagnostics) <= MAX_DIAGNOSTICS,
            "diagnostics is not a list")
    config_path = data["config_path"]
    _expect(config_path is None or _real(_path(config_path)) in verified,
            "the config is not an input")
    return LintResult(
        target=target,
        diagnostics=tuple(_diagnostic(d, verified, target) for d in diagnostics),
        suppressed=_count(data["suppressed"]), config_path=config_path,
        rules_run=tuple(_code(c) for c in _list(data["rules_run"], 10_000)),
        suppressed_by_config=_count(data["suppressed_by_config"]),
        inputs=RunInputs(tuple(RunInput(path, "a file the lint read")  # real paths already
                               for path in sorted(verified))))


def _diagnostic(data: Any, verified: set[str], target: str) -> Diagnostic:
    _expect(isinstance(data, dict), "a diagnostic is not an object")
    where = data["where"]
    fix = data["fix"]
    return Diagnostic(code=_code(data["code"]), name=_name(data["name"]),
                      severity=Severity[_text(data["severity"], 16).upper()],
                      message=_text(data["message"], MAX_TEXT),
                      where=None if where is None else _provenance(where, verified),
                      element=_text(data["element"], MAX_TEXT),
                      fix=None if fix is None else _text(fix, MAX_TEXT), target=target)


def _provenance(data: Any, verified: set[str]) -> Provenance:
    _expect(isinstance(data, list) and len(data) == 3, "where is not [span, stack, passed]")
    passed = []
    for item in _list(data[2], MAX_STACK):
        _expect(isinstance(item, list) and len(item) == 3, "a passed value is malformed")
        passed.append(PassedValue(_text(item[0], 1000), _text(item[1], 1000),
                                  _span(item[2], verified)))
    return Provenance(_span(data[0], verified),
                      tuple(_span(s, verified) for s in _list(data[1], MAX_STACK)),
                      tuple(passed))


def _span(data: Any, verified: set[str]) -> Span:
    """A stored span; its file must be a verified input (what robotdesc may show text of)."""
    _expect(isinstance(data, list) and len(data) == 3, "a span is not [path, line, col]")
    path = _path(data[0])
    _expect(path in verified or _real(path) in verified, "a span points outside the inputs")
    return Span(path, _count(data[1]), _count(data[2]))


@functools.lru_cache(maxsize=4096)
def _real(path: str) -> str:
    return os.path.realpath(path)


def _path(value: Any) -> str:
    _expect(isinstance(value, str) and 0 < len(value) <= MAX_PATH and os.path.isabs(value)
            and os.path.normpath(value) == value and _CONTROL.search(value) is None,
            "a path is not absolute and normal")
    return str(value)


def _text(value: Any, limit: int) -> str:
    _expect(isinstance(value, str) and len(value) <= limit and _CONTROL.search(value) is None,
            "a text is too long or holds control characters")
    return str(value)


def _code(value: Any) -> str:
    _expect(isinstance(value, str) and _CODE.fullmatch(value) is not None, "not a rule code")
    return str(value)


def _name(value: Any) -> str:
    _expect(isinstance(value, str) and len(value) <= 100 and _NAME.fullmatch(value) is not None,
            "not a rule name")
    return str(value)


def _count(value: Any) -> int:
    _expect(type(value) is int and 0 <= value <= MAX_COUNT, "not a count")
    return int(value)


def _list(value: Any, limit: int) -> list[Any]:
    _expect(isinstance(value, list) and len(value) <= limit, "not a list")
    return list(value)


def _expect(condition: bool, why: str) -> None:
    if not condition:
        raise _Invalid(why)


def store(key: CacheKey | None, result: LintResult, *, started_ns: int,
          env_names: Iterable[str] = (), complete: bool = True) -> None:
    """Record `result` (with its `inputs`) under `key`; nothing when the cache is off, the
    result is not `complete` (a mesh did not resolve), or an input vanished or changed after
    `started_ns` (`time.time_ns()` when the lint began).

    Args:
        env_names: environment variables whose presence the findings depend on.
    """
    if key is None or result.inputs is None:
        return
    inputs = []
    target = os.path.realpath(result.target)
    paths = [item.path for item in result.inputs.items]
    if not complete or target not in paths:
        return
    for path in paths:
        digest = _stable_digest(path, started_ns)
        if digest is None:
            log.debug("result cache: not stored (%s vanished or changed)", path)
            return
        inputs.append([path, digest])
    verified = set(paths)
    try:
        encoded = [_encode_diagnostic(d, verified) for d in result.diagnostics]
    except _Invalid as exc:  # a finding points outside the inputs: do not cache it
        log.debug("result cache: not stored (%s)", exc)
        return
    record = {
        "format": _FORMAT, "key": key.digest, "inputs": inputs,
        "env": {name: name in os.environ for name in sorted(set(env_names))},
        "result": {"diagnostics": encoded, "suppressed": result.suppressed,
                   "config_path": result.config_path and os.path.abspath(result.config_path),
                   "rules_run": list(result.rules_run),
                   "suppressed_by_config": result.suppressed_by_config}}
    try:
        write_entry(key.path, json.dumps(record).encode("utf-8"))
    except OSError as exc:
        log.warning("result cache: cannot write %s (%s)", key.path, exc)


def _stable_digest(path: str, started_ns: int) -> str | None:
    """The digest of an input that is its own real path, a regular file, and unmodified
    since the lint began (with slack for coarse clocks); else None."""
    try:
        info = os.lstat(path)
    except OSError:
        return None
    coarse = info.st_mtime_ns % 1_000_000_000 == 0  # a file system with whole-second times
    if not stat.S_ISREG(info.st_mode) or os.path.realpath(path) != path \
            or info.st_mtime_ns >= started_ns - (_MTIME_SLACK_NS if coarse else 0):
        return None
    return file_digest(path, follow_symlinks=False)


def _encode_diagnostic(diagnostic: Diagnostic, verified: set[str]) -> dict[str, Any]:
    where = diagnostic.where
    return {"code": diagnostic.code, "name": diagnostic.name,
            "severity": str(diagnostic.severity), "message": diagnostic.message,
            "where": None if where is None else [
                _encode_span(where.span, verified),
                [_encode_span(s, verified) for s in where.macro_stack],
                [[p.element, p.attribute, _encode_span(p.span, verified)]
                 for p in where.passed]],
            "element": diagnostic.element, "fix": diagnostic.fix}


def _encode_span(span: Span, verified: set[str]) -> list[str | int]:
    path = os.path.abspath(span.path) if span.path else ""
    _expect(path in verified or os.path.realpath(path) in verified,
            f"a finding points at {span.path!r}, not an input")
    return [path, span.line, span.col]
