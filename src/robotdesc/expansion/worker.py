"""The xacro worker: runs in its own process, reads a job (JSON) on stdin, writes a result.

Started by `robotdesc.expansion.runner`; never imported by the parent process (it patches xacro).
The result is one JSON object on stdout: {"ok": true, ...} or {"ok": false, "kind", "message",
"span", "call_stack"}. Everything xacro prints goes to stderr.
"""

from __future__ import annotations

import difflib
import errno
import gc
import json
import math  # noqa: F401 -- everything the worker needs is imported before confinement
import os
import sys
import threading
import traceback
import xml.dom.expatbuilder
import xml.dom.minidom
import xml.parsers.expat
from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING, cast

import xacro
import xacro.substitution_args
import yaml  # noqa: F401 -- xacro.load_yaml imports it lazily

from robotdesc.expansion import confine, hooks, sandbox
from robotdesc.expansion.packages import PackageResolver, PackageResolverConfig
from robotdesc.expansion.result import ResolvedPackage
from robotdesc.forked import die_with_parent

if TYPE_CHECKING:
    from typing import TypedDict

    class _ResolverSettings(TypedDict):
        """`PackageResolverConfig`'s fields, as the worker rebuilds them from the job."""

        origin: str
        package_paths: tuple[str, ...]
        package_map: tuple[tuple[str, str], ...]
        ros_package_path: str
        ament_prefix_path: str

    class _JobBase(TypedDict):
        """The job the runner sends (JSON: tuples arrive as lists)."""

        file: str
        args: list[list[str]]
        resolver: dict[str, object]
        trusted: bool
        env: dict[str, str]
        memory_mb: int
        cpu_seconds: int
        max_macro_depth: int
        max_output_bytes: int
        known: list[list[str]]
        data_roots: list[str]
        guard_roots: list[str]

    class _Job(_JobBase, total=False):
        env_names: list[str]

#: Stack for the expansion thread: xacro recurses once per nested element and macro call.
_THREAD_STACK_BYTES = 256 * 1024 * 1024
_RECURSION_LIMIT = 200_000
#: The collector's thresholds during the expansion (Python's default: 700, 10, 10).
_GC_THRESHOLDS = (10_000, 10, 10)


def _span(src: str, files: list[str]) -> list[str | int] | None:
    """[file, line, column] of a "FILE_INDEX:LINE" provenance value."""
    if not src:
        return None
    index, _, line = src.partition(":")
    return [files[int(index)], int(line), 0]


def _failure(kind: str, message: str, span: list[str | int] | None = None,
             chain: Iterable[list[str | int] | None] = ()) -> dict[str, object]:
    return {"ok": False, "kind": kind, "message": message, "span": span, "call_stack": list(chain)}


def _root_cause(exc: BaseException) -> BaseException:
    """Walk xacro's wrappers (`exc.exc`) and Python's chaining down to the first cause."""
    seen = set()
    while id(exc) not in seen:
        seen.add(id(exc))
        inner = getattr(exc, "exc", None) or exc.__cause__ or exc.__context__
        if not isinstance(inner, BaseException):
            break
        exc = inner
    return exc


def _chain(exc: BaseException) -> Iterator[BaseException]:
    """`exc` and every exception it wraps or was raised from."""
    seen = set()
    item: object = exc
    while isinstance(item, BaseException) and id(item) not in seen:
        seen.add(id(item))
        yield item
        item = getattr(item, "exc", None) or item.__cause__ or item.__context__


def _os_refusal(exc: BaseException, guard: sandbox.Guard | None) -> BaseException | None:
    """The OSError or ImportError in `exc`'s chain that the OS confinement caused, if any.

    A file inside the packages in use that its own permissions make unreadable is the file's
    problem, not the sandbox's (Landlock does not answer `access()`).
    """
    for item in _chain(exc):
        if isinstance(item, OSError) and item.errno in (errno.EPERM, errno.EACCES):
            name = item.filename if isinstance(item.filename, str) else ""
            if guard is not None and name and sandbox.is_within(name, guard.data_roots) \
                    and os.path.exists(name) and not os.access(name, os.R_OK):
                return None
            return item
        if isinstance(item, ImportError) and "Permission denied" in str(item):
            return item
    return None


def _missing_arg(exc: BaseException) -> str | None:
    for item in _chain(exc):
        if isinstance(item, xacro.substitution_args.ArgException):
            return str(item.args[0]) if item.args else str(item)
    return None


def _classify(exc: BaseException, guard: sandbox.Guard | None = None) -> str:
    cause = _root_cause(exc)
    if guard is not None and guard.safe and _os_refusal(exc, guard) is not None:
        return "SandboxViolation"
    for candidate in (exc, cause):
        if isinstance(candidate, sandbox.Forbidden):
            return "SandboxViolation"
        if isinstance(candidate, hooks.IncludeCycle):
            return "ExpansionError"
        if isinstance(candidate, hooks.MacroTooDeep):
            return "LimitExceeded"
        if isinstance(candidate, (MemoryError, RecursionError)):
            return "LimitExceeded"
        if type(candidate).__name__ == "_UnknownPackage":
            return "PackageNotFoundError"
    return "ExpansionError"


def _message(exc: BaseException, guard: sandbox.Guard | None = None,
             declared: tuple[str, ...] = ()) -> str:
    cause = _root_cause(exc)
    refusal = _os_refusal(exc, guard) if guard is not None and guard.safe else None
    if refusal is not None:
        what = getattr(refusal, "strerror", None) or str(refusal)
        target = getattr(refusal, "filename", None)
        where = f" ('{target}')" if isinstance(target, str) else ""
        return (f"the sandbox refused an operation of a xacro expression: {what}{where}; "
                "the file tried to reach outside the packages in use (use --trusted only "
                "for files you trust)")
    missing = _missing_arg(exc)
    if missing is not None:
        close = difflib.get_close_matches(missing, declared, 1)
        hint = f" (did you mean '{close[0]}'?)" if close else ""
        return f"xacro argument '{missing}' has no default; pass {missing}:=VALUE{hint}"
    if isinstance(cause, MemoryError):
        return "memory limit hit while evaluating an expression (a xacro expression built a huge value)"
    if isinstance(cause, RecursionError):
        return "recursion limit hit (a macro or property refers to itself without end?)"
    if isinstance(cause, (sandbox.Forbidden, hooks.MacroTooDeep, hooks.IncludeCycle)) \
            or type(cause).__name__ == "_UnknownPackage":
        return str(cause)
    if isinstance(cause, KeyError):
        return f"undefined name {cause} (an unknown macro, block or dictionary key)"
    if cause is not exc and str(cause):
        kind = "invalid expression: " if isinstance(cause, SyntaxError) else ""
        suffix = getattr(exc, "suffix", None) or ""
        text = f"{kind}{cause} {suffix}"
    else:
        text = str(exc) or repr(exc)
    text = " ".join(text.split())
    return text if len(text) < 2000 else text[:2000] + "..."


def _bounded(chain: tuple[str, ...], keep_inner: int = 8,
             keep_outer: int = 4) -> tuple[str, ...]:
    """At most a dozen call sites: the innermost and the outermost ones."""
    if len(chain) <= keep_inner + keep_outer:
        return chain
    return chain[:keep_inner] + chain[-keep_outer:]


class _UnknownPackage(Exception):
    def __init__(self, name: str, searched: tuple[str, ...]) -> None:
        where = "; searched: " + ", ".join(searched) if searched else ""
        super().__init__(f"unknown package '{name}'{where}")
        self.name = name


def _resolver(job: _Job) -> PackageResolver:
    settings = {k: tuple(tuple(x) if isinstance(x, list) else x for x in v) if isinstance(v, list)
                else v for k, v in job["resolver"].items()}
    known = [ResolvedPackage(*entry) for entry in job["known"]]
    # JSON lists made tuples again: the fields of `dataclasses.asdict(PackageResolverConfig)`
    return PackageResolver(PackageResolverConfig(**cast("_ResolverSettings", settings)),
                           known=known)


def run_job(job: _Job, guard: sandbox.Guard) -> dict[str, object]:
    """Expand the job's file; return the result dictionary."""
    resolver = _resolver(job)
    top = os.path.abspath(job["file"])
    for folder in job["guard_roots"]:
        guard.allow_root(folder)
    state = hooks.ExpansionState(max_macro_depth=job["max_macro_depth"])
    passed = hooks.RecordingArgs(dict(job["args"]))

    def find_package(name: str) -> str:
        found = resolver.find(name)
        if found is None:
            raise _UnknownPackage(name, resolver.searched())
        guard.allow_root(found.path)
        return found.path

    def check_file(path: str) -> None:
        if guard.safe and not sandbox.is_within(path, guard.data_roots):
            raise sandbox.Forbidden(
                f"include of '{path}' escapes the package root ({', '.join(guard.data_roots)}); "
                "safe mode refuses it (use --package-path for another package, or --trusted)")

    hooks.install(state, find_package, check_file)
    hooks.install_environment(job["env"], guard.safe, state, frozenset(job.get("env_names", ())))
    xacro.verbosity = 0
    guard.armed = True
    try:
        xacro.init_stacks(top)
        doc = xacro.parse(None, top)
        xacro.process_doc(doc, mappings=passed)
        text = doc.documentElement.toxml()
    except hooks.DoctypeRefused as exc:
        return _failure("XmlSyntaxError", str(exc), [exc.path, exc.line, exc.col])
    except xml.parsers.expat.ExpatError as exc:
        path = getattr(exc, "robotdesc_path", top)
        message = xml.parsers.expat.ErrorString(exc.code) if exc.code else str(exc)
        return _failure("XmlSyntaxError", f"malformed XML: {message}", [path, exc.lineno, exc.offset + 1])
    except BaseException as exc:  # noqa: BLE001 -- every failure is reported, none is hidden
        src, chain = state.error_src or (state.last_src, ())
        cause = _root_cause(exc)
        if isinstance(cause, xml.parsers.expat.ExpatError):
            path = getattr(cause, "robotdesc_path", top)
            return _failure("XmlSyntaxError", f"malformed XML: {xml.parsers.expat.ErrorString(cause.code)}",
                            [path, cause.lineno, cause.offset + 1])
        return _failure(_classify(exc, guard), _message(exc, guard, tuple(state.declared_args)),
                        _span(src, state.files), [_span(c, state.files) for c in _bounded(chain) if c])
    finally:
        guard.armed = False
    recursion = [[name, depth, _span(defined, state.files), _span(called, state.files)]
                 for name, (depth, defined, called) in sorted(state.recursion.items())]
    if len(text) > job["max_output_bytes"]:
        return _failure("LimitExceeded", f"expanded document larger than {job['max_output_bytes']} bytes")
    return {"ok": True, "xml": text, "files": state.files, "files_read": guard.files_read,
            "packages": [[p.name, p.path, p.source] for p in resolver.resolved],
            "macro_recursion": recursion,
            "declared_args": [[name, _span(src, state.files)]
                              for name, src in state.declared_args.items()],
            "read_args": sorted(passed.read),
            "env_defaults": [[name, default, _span(src, state.files)]
                             for name, default, src in state.env_defaults]}


def main(parent_pid: int | None = None) -> None:
    """Read the job, confine this process (safe mode), expand in a thread, answer.

    Args:
        parent_pid: the robotdesc process that started this worker: the worker ends when
            it ends (and at once if it has already gone).
    """
    if parent_pid is not None:
        die_with_parent(parent_pid)
    # what confining needs (libseccomp, found by two `ldconfig` runs) before the job arrives:
    # a worker started early waits for it (`robotdesc.expansion.launch`)
    confine.probe()
    job: _Job = json.loads(sys.stdin.read())
    sandbox.apply_limits(job["memory_mb"], job["cpu_seconds"])
    guard = sandbox.Guard(safe=not job["trusted"], code_roots=confine.code_roots())
    sandbox.install(guard)
    real_stdout = sys.stdout
    sys.stdout = sys.stderr  # xacro prints; keep stdout for the result
    sys.setrecursionlimit(_RECURSION_LIMIT)
    threading.stack_size(_THREAD_STACK_BYTES)
    # the modules and the job live as long as the process: the collector leaves them out,
    # and runs less often on the many small objects of a document (a fifth of the expansion's
    # time with the defaults); cyclic garbage is still collected
    gc.freeze()
    gc.set_threshold(*_GC_THRESHOLDS)
    outcome: dict[str, object] = {}
    if guard.safe:
        try:  # before any xacro expression runs and before the expansion thread starts
            confine.confine(job["data_roots"], guard.code_roots)
        except confine.ConfinementError as exc:
            real_stdout.write(json.dumps(_failure("SandboxUnavailable", str(exc))))
            real_stdout.flush()
            return

    def target() -> None:
        try:
            outcome.update(run_job(job, guard))
        except BaseException as exc:  # noqa: BLE001 -- reported to the parent as an internal error
            outcome.update(_failure("InternalError", f"{type(exc).__name__}: {exc}",
                                    None, ()), traceback=traceback.format_exc())

    thread = threading.Thread(target=target, name="xacro")
    thread.start()
    thread.join()
    real_stdout.write(json.dumps(outcome))
    real_stdout.flush()
    sys.stderr.flush()
    # the answer is out: end now, without tearing the document's objects down one by one
    # (tens of ms for a large robot, while the parent waits for the end of the output)
    os._exit(0)


if __name__ == "__main__":
    main()
