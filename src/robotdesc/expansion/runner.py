"""Run the xacro worker in a separate, limited process and turn its answer into values."""

from __future__ import annotations

import dataclasses
import json
import logging
import os
import signal
import subprocess
import sys
from pathlib import Path
from typing import Any

from robotdesc import errors
from robotdesc.expansion import confine
from robotdesc.expansion.packages import PackageResolver, PackageResolverConfig
from robotdesc.expansion.result import EnvDefault, Expanded, MacroRecursion, ResolvedPackage
from robotdesc.expansion.sandbox import is_within
from robotdesc.source import Span

log = logging.getLogger(__name__)

#: Whether the "cannot confine" warning was logged in this process (it is logged once).
_WARNED_UNCONFINED: list[bool] = []
#: Characters of the worker's stderr passed through to the log (no terminal control codes).
_PRINTABLE = {c: None for c in range(32) if c not in (9,)} | {127: None}

_ERROR_KINDS = {
    "XmlSyntaxError": errors.XmlSyntaxError,
    "ExpansionError": errors.ExpansionError,
    "SandboxViolation": errors.SandboxViolation,
    "LimitExceeded": errors.LimitExceeded,
    "PackageNotFoundError": errors.ExpansionError,
    "SandboxUnavailable": errors.SandboxUnavailable,
}


@dataclasses.dataclass(frozen=True)
class WorkerLimits:
    """Limits of one expansion.

    Attributes:
        timeout_s: wall-clock seconds before the worker is killed.
        memory_mb: address-space cap of the worker (MiB).
        max_macro_depth: nested macro calls allowed.
        max_output_bytes: largest expanded document accepted.
    """

    timeout_s: float = 60.0
    memory_mb: int = 2048
    max_macro_depth: int = 2000
    max_output_bytes: int = 256 * 1024 * 1024


def _worker_pythonpath() -> str:
    """Where the worker finds robotdesc and installed packages (never the current folder)."""
    own = str(Path(__file__).resolve().parents[2])
    site = [p for p in sys.path if p and ("site-packages" in p or "dist-packages" in p)]
    return os.pathsep.join(dict.fromkeys([own, *site]))


def _worker_environment() -> dict[str, str]:
    env = {"PYTHONPATH": _worker_pythonpath(), "PATH": os.defpath, "LC_ALL": "C.UTF-8",
           "PYTHONDONTWRITEBYTECODE": "1", "PYTHONIOENCODING": "utf-8"}
    return env


def require_confinement(path: Path) -> None:
    """Refuse untrusted expansion where the worker cannot be confined (warned once).

    Raises:
        SandboxUnavailable: Landlock or seccomp is missing (or this is not Linux).
    """
    support = confine.probe()
    if support.available:
        return
    if not _WARNED_UNCONFINED:
        _WARNED_UNCONFINED.append(True)
        log.warning("cannot confine the xacro worker here: %s; untrusted xacro files will not "
                    "be expanded (pass --trusted only for files you trust)", support.reason)
    raise errors.SandboxUnavailable(
        f"refusing to expand xacro without OS confinement ({support.reason}); a xacro file "
        "is code: pass --trusted only for files you trust", Span(str(path)))


@dataclasses.dataclass(frozen=True)
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


def worker_roots(path: Path, resolver: PackageResolverConfig) -> Roots:
    """Resolve the whole package chain now (in the parent) and derive the readable roots.

    The data roots are the top file's package (or its folder when it has none), every
    package folder the chain can return and the config's package folders; a `--package-path`
    folder holding no package is a root itself. Never a whole workspace.
    """
    chain = PackageResolver(resolver)
    known = chain.candidates()
    top_root = str(chain.enclosing[1]) if chain.enclosing else str(path.resolve().parent)
    explicit = []
    for folder in resolver.package_paths:
        inside = [p.path for p in known if p.source == "--package-path" and is_within(p.path, (folder,))]
        explicit.extend(inside or [folder])
    mapped = [folder for _, folder in resolver.package_map]
    data = tuple(dict.fromkeys([top_root, *explicit, *mapped, *(p.path for p in known)]))
    return Roots(known, data, tuple(dict.fromkeys([top_root, *explicit])))


def run_worker(path: Path, args: dict[str, str], resolver: PackageResolverConfig, *,
               trusted: bool, env: dict[str, str], limits: WorkerLimits,
               env_names: tuple[str, ...] = ()) -> Expanded:
    """Expand `path` in a worker process (confined by the OS unless `trusted`).

    Args:
        env_names: names (never values) of variables set in the caller's environment,
            so that the worker can say which one was not passed.

    Raises:
        InputError subclasses: the file could not be expanded (with file:line when known).
        RobotdescError: the worker failed in a way that is robotdesc's bug.
    """
    if not trusted:
        require_confinement(path)
    roots = worker_roots(path, resolver)
    job = {
        "file": str(path), "args": sorted(args.items()), "resolver": dataclasses.asdict(resolver),
        "trusted": trusted, "env": env, "memory_mb": limits.memory_mb,
        "cpu_seconds": max(1, int(limits.timeout_s) + 1), "max_macro_depth": limits.max_macro_depth,
        "max_output_bytes": limits.max_output_bytes,
        "known": [[p.name, p.path, p.source] for p in roots.known],
        "data_roots": list(roots.data), "guard_roots": list(roots.guard),
        "env_names": sorted(env_names),
    }
    # -S: no site module (its .pth hooks cost 5-30 ms and run code the worker does not need);
    # the worker gets the parent's import path instead, without the current folder.
    search_path = [entry for entry in sys.path if entry]
    bootstrap = (f"import sys; sys.path[:] = {search_path!r}; "
                 "from robotdesc.expansion.worker import main; main()")
    command = [sys.executable, "-B", "-S", *(["-P"] if sys.version_info >= (3, 11) else []),
               "-c", bootstrap]
    try:
        proc = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, env=_worker_environment(),
                                start_new_session=True)
    except OSError as exc:
        raise errors.RobotdescError(f"cannot start the xacro worker: {exc}") from exc
    try:
        out, err = proc.communicate(json.dumps(job).encode(), timeout=limits.timeout_s)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        raise errors.LimitExceeded(
            f"expansion took longer than {limits.timeout_s:g} s and was stopped (a long-running "
            "expression, or a macro that recurses without end); raise the limit with --timeout",
            Span(str(path)))
    for line in err.decode("utf-8", "replace").splitlines():
        if line.strip():
            log.warning("xacro: %s", line.translate(_PRINTABLE))
    if proc.returncode != 0 or not out:
        raise _crash(proc.returncode, path, limits)
    try:
        answer = json.loads(out)
        if not answer["ok"]:
            raise _failure(answer, path)
        expanded = _expanded(answer, path, args)
    except (ValueError, KeyError, TypeError, IndexError) as exc:
        raise _garbled(path, trusted) from exc
    if not trusted:
        _check_answer(expanded, roots, path)
    return expanded


def _garbled(path: Path, trusted: bool) -> errors.InputError:
    """The worker's answer is not what the worker writes: an expression wrote to its output."""
    text = ("the xacro worker's answer was garbled (an expression wrote to the worker's "
            "output?)")
    if trusted:
        return errors.ExpansionError(text, Span(str(path)))
    return errors.SandboxViolation(f"{text}; the sandbox refused the result", Span(str(path)))


def _check_answer(expanded: Expanded, roots: Roots, path: Path) -> None:
    """Refuse an answer that names files or packages the confined worker could not have used.

    The answer comes from a process that ran untrusted code; the parent reads the files it
    names (suppression comments, cache digests), so they must lie inside the data roots.
    """
    for name in (*expanded.files, *expanded.files_read):
        if name == "<string>":
            continue
        if not os.path.isabs(name) or not is_within(name, roots.data):
            raise errors.SandboxViolation(
                f"the xacro worker's answer names '{name}', outside the packages in use; "
                "the sandbox refused the result", Span(str(path)))
    known = set(roots.known)
    for package in expanded.packages:
        if package not in known:
            raise errors.SandboxViolation(
                f"the xacro worker's answer names package '{package.name}' at {package.path}, "
                "which the resolver does not know; the sandbox refused the result",
                Span(str(path)))


def _crash(returncode: int, path: Path, limits: WorkerLimits) -> errors.RobotdescError:
    if returncode == -signal.SIGSYS:
        return errors.SandboxViolation(
            "the sandbox stopped the xacro worker: an expression made a system call it "
            "forbids (starting a program or process, opening a socket, changing file "
            "attributes, signalling another process, ...); use --trusted only for files you "
            "trust", Span(str(path)))
    if returncode in (-signal.SIGXCPU, -signal.SIGKILL):
        return errors.LimitExceeded(f"expansion hit the CPU limit ({int(limits.timeout_s) + 1} s)",
                                    Span(str(path)))
    if returncode == -signal.SIGSEGV or returncode == 1:
        return errors.LimitExceeded(f"the xacro worker ran out of memory or stack "
                                    f"(limit {limits.memory_mb} MiB)", Span(str(path)))
    return errors.RobotdescError(f"the xacro worker died (exit status {returncode})")


def _span(value: list[Any] | None) -> Span | None:
    return Span(value[0], value[1], value[2] if len(value) > 2 else 0) if value else None


def _failure(answer: dict[str, Any], path: Path) -> errors.RobotdescError:
    kind = answer["kind"]
    if kind == "InternalError":
        log.debug("worker traceback:\n%s", answer.get("traceback", ""))
        return errors.RobotdescError(f"internal error in the xacro worker: {answer['message']}")
    span = _span(answer.get("span")) or Span(str(path))
    chain = tuple(s for s in (_span(c) for c in answer.get("call_stack", ())) if s)
    return _ERROR_KINDS[kind](answer["message"], span, chain)


def _expanded(answer: dict[str, Any], path: Path, args: dict[str, str]) -> Expanded:
    recursion = tuple(MacroRecursion(name, depth, _span(defined) or Span(str(path)), _span(called))
                      for name, depth, defined, called in answer["macro_recursion"])
    return Expanded(
        source=str(path), xml=answer["xml"].encode("utf-8"), files=tuple(answer["files"]),
        files_read=tuple(answer["files_read"]),
        packages=tuple(ResolvedPackage(*p) for p in answer["packages"]),
        macro_recursion=recursion, from_xacro=True, args=tuple(sorted(args.items())),
        declared_args=tuple((name, _span(span) or Span(str(path)))
                            for name, span in answer.get("declared_args", ())),
        read_args=tuple(answer.get("read_args", ())),
        env_defaults=tuple(EnvDefault(name, default, _span(span) or Span(str(path)))
                           for name, default, span in answer.get("env_defaults", ())))
