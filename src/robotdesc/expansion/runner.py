"""Run the xacro worker in a separate, limited process and turn its answer into values."""

from __future__ import annotations

import dataclasses
import json
import logging
import signal
from collections.abc import Callable
from pathlib import Path

from robotdesc import errors
from robotdesc.expansion import confine, launch
from robotdesc.expansion.answer import (
    MAX_TEXT,
    check_expanded,
    check_paths,
    check_provenance,
    invalid,
    max_chain,
    parse_expanded,
    parse_failure,
)
from robotdesc.expansion.exchange import exchange, worker_group
from robotdesc.expansion.packages import PackageResolverConfig
from robotdesc.expansion.result import Expanded
from robotdesc.expansion.roots import Roots, worker_roots
from robotdesc.printable import printable
from robotdesc.source import Span

log = logging.getLogger(__name__)

#: Whether the "cannot confine" warning was logged in this process (it is logged once).
_WARNED_UNCONFINED: list[bool] = []

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


def run_worker(path: Path, args: dict[str, str], resolver: PackageResolverConfig, *,
               trusted: bool, env: dict[str, str], limits: WorkerLimits,
               env_names: tuple[str, ...] = (),
               while_waiting: Callable[[], object] | None = None) -> Expanded:
    """Expand `path` in a worker process (confined by the OS unless `trusted`).

    Args:
        env_names: names (never values) of variables set in the caller's environment,
            so that the worker can say which one was not passed.
        while_waiting: called once the worker has its job, in this thread, while it expands
            (this process then only waits for its answer).

    Raises:
        InputError subclasses: the file could not be expanded (with file:line when known).
        RobotdescError: the worker failed in a way that is robotdesc's bug.
    """
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
    proc = launch.take_early()
    if proc is None:
        try:
            proc = launch.launch()
        except OSError as exc:
            raise errors.RobotdescError(f"cannot start the xacro worker: {exc}") from exc
    def waiting() -> None:
        # the worker confines itself before any xacro runs (else it answers why not): this
        # only says why first, without delaying the job (the probe runs `ldconfig` twice)
        if not trusted:
            require_confinement(path)
        if while_waiting is not None:
            while_waiting()

    with worker_group(proc):
        exchanged = exchange(proc, json.dumps(job).encode(), limits.timeout_s,
                             answer_cap(limits.max_output_bytes), waiting)
    launch.start_next()
    if exchanged.timed_out:
        raise errors.LimitExceeded(
            f"expansion took longer than {limits.timeout_s:g} s and was stopped (a long-running "
            "expression, or a macro that recurses without end); raise the limit with --timeout",
            Span(str(path)))
    for line in exchanged.err.decode("utf-8", "replace").splitlines():
        if line.strip():
            log.warning("xacro: %s", printable(line))
    if exchanged.err_dropped:
        log.warning("xacro: %d more bytes of the worker's messages were dropped",
                    exchanged.err_dropped)
    if exchanged.overflow:
        raise errors.LimitExceeded(
            f"the xacro worker wrote more than {answer_cap(limits.max_output_bytes)} bytes of "
            "answer and was stopped (the output-size limit)", Span(str(path)))
    if proc.returncode != 0 or not exchanged.out:
        raise _crash(proc.returncode, path, limits)
    return _accept(exchanged.out, path, args, roots, trusted, limits)


def answer_cap(max_output_bytes: int) -> int:
    """The most bytes of answer read from the worker: the document's limit, JSON's escapes
    and the file tables."""
    return 2 * max_output_bytes + (16 << 20)


def _accept(out: bytes, path: Path, args: dict[str, str], roots: Roots, trusted: bool,
            limits: WorkerLimits) -> Expanded:
    """The expansion in the worker's answer, checked (see `robotdesc.expansion.answer`).

    Raises:
        InputError: the failure the worker reports (exit 2, whatever kind it names), or
            InvalidAnswer when the answer is malformed or names what the parent cannot justify.
    """
    try:
        answer = json.loads(out)
    except (ValueError, RecursionError):
        raise _garbled(path, trusted) from None
    if not isinstance(answer, dict) or not isinstance(answer.get("ok"), bool):
        raise _garbled(path, trusted)
    if not answer["ok"]:
        failure, named = parse_failure(answer, path)
        if not trusted:
            check_paths(named, roots, path)
        if answer.get("kind") == "InternalError":
            log.debug("worker traceback:\n%s", str(answer.get("traceback", ""))[:MAX_TEXT])
        raise failure
    expanded = parse_expanded(answer, path, args, limits.max_output_bytes)
    if trusted:
        check_provenance(expanded, path, max_chain(limits.max_macro_depth))
    else:
        check_expanded(expanded, roots, path, max_chain(limits.max_macro_depth))
    return expanded


def _garbled(path: Path, trusted: bool) -> errors.InputError:
    """The worker's answer is not what the worker writes: an expression wrote to its output."""
    text = ("the xacro worker's answer was garbled (an expression wrote to the worker's "
            "output?)")
    if trusted:
        return errors.ExpansionError(text, Span(str(path)))
    return invalid(path, "garbled: not the JSON object the worker writes")


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
    # the worker ran the description's code, which can end it any way it likes
    return errors.ExpansionError(
        f"the xacro worker ended without an answer (exit status {returncode}); an expression "
        "in the description may have ended it", Span(str(path)))
