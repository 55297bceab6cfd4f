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

from robotdesc import errors
from robotdesc.expansion.packages import PackageResolverConfig
from robotdesc.expansion.result import Expanded, ResolvedPackage
from robotdesc.rules.registry import MacroRecursion
from robotdesc.source import Span

log = logging.getLogger(__name__)

_ERROR_KINDS = {
    "XmlSyntaxError": errors.XmlSyntaxError,
    "ExpansionError": errors.ExpansionError,
    "SandboxViolation": errors.SandboxViolation,
    "LimitExceeded": errors.LimitExceeded,
    "PackageNotFoundError": errors.ExpansionError,
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


def run_worker(path: Path, args: dict[str, str], resolver: PackageResolverConfig, *,
               trusted: bool, env: dict[str, str], limits: WorkerLimits,
               extra_roots: tuple[str, ...] = ()) -> Expanded:
    """Expand `path` in a worker process.

    Raises:
        InputError subclasses: the file could not be expanded (with file:line when known).
        RobotdescError: the worker failed in a way that is robotdesc's bug.
    """
    job = {
        "file": str(path), "args": sorted(args.items()), "resolver": dataclasses.asdict(resolver),
        "trusted": trusted, "env": env, "memory_mb": limits.memory_mb,
        "cpu_seconds": max(1, int(limits.timeout_s) + 1), "max_macro_depth": limits.max_macro_depth,
        "max_output_bytes": limits.max_output_bytes, "extra_roots": list(extra_roots),
    }
    command = [sys.executable, "-B", "-c", "from robotdesc.expansion.worker import main; main()"]
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
            f"expansion took longer than {limits.timeout_s:g} s and was stopped "
            "(a macro that recurses without end? raise the limit with --timeout)", Span(str(path)))
    for line in err.decode("utf-8", "replace").splitlines():
        if line.strip():
            log.warning("xacro: %s", line)
    if proc.returncode != 0 or not out:
        raise _crash(proc.returncode, path, limits)
    answer = json.loads(out)
    if not answer["ok"]:
        raise _failure(answer, path)
    return _expanded(answer, path, args)


def _crash(returncode: int, path: Path, limits: WorkerLimits) -> errors.RobotdescError:
    if returncode in (-signal.SIGXCPU, -signal.SIGKILL):
        return errors.LimitExceeded(f"expansion hit the CPU limit ({int(limits.timeout_s) + 1} s)",
                                    Span(str(path)))
    if returncode == -signal.SIGSEGV or returncode == 1:
        return errors.LimitExceeded(f"the xacro worker ran out of memory or stack "
                                    f"(limit {limits.memory_mb} MiB)", Span(str(path)))
    return errors.RobotdescError(f"the xacro worker died (exit status {returncode})")


def _span(value) -> Span | None:
    return Span(value[0], value[1], value[2] if len(value) > 2 else 0) if value else None


def _failure(answer: dict, path: Path) -> errors.RobotdescError:
    kind = answer["kind"]
    if kind == "InternalError":
        log.debug("worker traceback:\n%s", answer.get("traceback", ""))
        return errors.RobotdescError(f"internal error in the xacro worker: {answer['message']}")
    span = _span(answer.get("span")) or Span(str(path))
    chain = tuple(s for s in (_span(c) for c in answer.get("call_stack", ())) if s)
    return _ERROR_KINDS[kind](answer["message"], span, chain)


def _expanded(answer: dict, path: Path, args: dict[str, str]) -> Expanded:
    recursion = tuple(MacroRecursion(name, depth, _span(defined) or Span(str(path)), _span(called))
                      for name, depth, defined, called in answer["macro_recursion"])
    return Expanded(
        source=str(path), xml=answer["xml"].encode("utf-8"), files=tuple(answer["files"]),
        files_read=tuple(answer["files_read"]),
        packages=tuple(ResolvedPackage(*p) for p in answer["packages"]),
        macro_recursion=recursion, from_xacro=True, args=tuple(sorted(args.items())))
