"""Lint many targets, in this process or across worker processes (`lint --jobs N`).

A target whose inputs did not change since a run with the same settings is a read of the
whole-result cache (`robotdesc.linting.result_cache`): it is neither expanded nor linted.

Workers share robotdesc's on-disk caches (expansions and mesh summaries, both keyed by
content and written atomically), so a mesh used by several targets is summarized once per
cache, not once per worker. Results come back in the order of the targets, whatever the
number of jobs, so reports do not depend on scheduling.
"""

from __future__ import annotations

import dataclasses
import logging
import os
import threading
import time
import traceback
from dataclasses import dataclass
from typing import Any, Callable, Mapping, Sequence

from robotdesc.errors import InputError, OptionError, UsageError, WorkerCrashed
from robotdesc.expansion import ExpandOptions
from robotdesc.expansion.packages import package_lookup
from robotdesc.linting import result_cache
from robotdesc.linting.cached import cached_result as cached_result  # re-exported
from robotdesc.linting.cached import target_key
from robotdesc.linting.driver import lint_file
from robotdesc.linting.inputs import inputs_locator, meshes_resolve, run_inputs
from robotdesc.linting.result import LintFailure, LintResult
from robotdesc.linting.targets import LintTarget

log = logging.getLogger(__name__)

Outcome = LintResult | LintFailure


@dataclass(frozen=True)
class _Crash:
    """A bug in a worker, carried back as text (exceptions do not always pickle)."""

    target: str
    summary: str
    trace: str


def effective_jobs(jobs: int) -> int:
    """`jobs`, where 0 means one per CPU.

    Raises:
        OptionError: `jobs` is negative.
    """
    if jobs < 0:
        raise OptionError("jobs", jobs, f"jobs must be 0 (one per CPU) or positive, got {jobs}")
    return jobs or os.cpu_count() or 1


def lint_targets(targets: Sequence[LintTarget], *, args: Mapping[str, str] | None = None,
                 expand_options: ExpandOptions | None = None,
                 select: Sequence[str] | None = None,
                 ignore: Sequence[str] = (), jobs: int = 1, scheduler: str | None = None,
                 on_done: Callable[[int], None] | None = None) -> list[Outcome]:
    """Lint every target; one `LintResult` or `LintFailure` per target, in target order.

    The results carry diagnostics only (`expanded` and `robot` are dropped so that they
    travel cheaply between processes); use `lint_file` for the model.

    Args:
        targets: what to lint (see `discover_targets`).
        args: command-line xacro arguments; they override the targets' own.
        expand_options: `robotdesc.expansion.ExpandOptions` for every target.
        select: rule selectors that replace each config's `select`.
        ignore: rule selectors added to each config's `ignore`.
        jobs: worker processes (1: lint in this process; 0: one per CPU); with a scheduler,
            the worker processes of `local`.
        scheduler: lint on a Dask cluster: its address (`tcp://host:8786`), or "local" for
            a cluster of `jobs` worker processes on this machine started for the run. The
            targets' files must be at the same paths on every Dask worker (a shared file
            system); robotdesc[dask] must be installed there too.
        on_done: called with the number of targets done so far, as each one ends.

    Raises:
        WorkerCrashed / RuleCrashed: a bug while linting a target (exit code 3).
        UsageError: a scheduler that does not answer, or `distributed` is not installed.
    """
    effective_jobs(jobs)
    result_cache.new_run()
    found: dict[int, Outcome] = {}
    for number, target in enumerate(targets):
        hit = cached_result(target, args or {}, expand_options, select, ignore)
        if hit is not None:
            found[number] = hit
    missing = [number for number in range(len(targets)) if number not in found]
    work = [(targets[number], dict(args or {}), expand_options, select, tuple(ignore))
            for number in missing]
    done = len(found)
    if on_done is not None and done:
        on_done(done)

    def one_more(*_: object) -> None:
        nonlocal done
        done += 1
        if on_done is not None:
            on_done(done)

    local_jobs = min(effective_jobs(jobs), max(1, len(work)))
    outcomes: list[Outcome | _Crash]
    if not work:
        outcomes = []
    elif scheduler is not None:
        outcomes = _on_cluster(work, scheduler, effective_jobs(jobs), one_more)
    elif local_jobs == 1:
        outcomes = []
        for item in work:
            outcomes.append(_lint_one(*item, keep_exceptions=True))
            one_more()
    else:
        from concurrent.futures import ProcessPoolExecutor

        log.info("linting %d targets in %d worker processes", len(work), local_jobs)
        with ProcessPoolExecutor(max_workers=local_jobs, mp_context=_context()) as pool:
            outcomes = []
            for finished in pool.map(_lint_one, *zip(*work)):
                outcomes.append(finished)
                one_more()
    for number, outcome in zip(missing, outcomes):
        if isinstance(outcome, _Crash):
            raise WorkerCrashed(outcome.target, outcome.summary, outcome.trace)
        found[number] = outcome
    return [found[number] for number in range(len(targets))]


#: Wall-clock limit of one target's lint on a Dask worker (s); time queued does not count.
CLUSTER_TASK_TIMEOUT_S = 3600.0


def _on_cluster(work: list[tuple[Any, ...]], scheduler: str, jobs: int,
                on_done: Callable[..., None]) -> list[Outcome | _Crash]:
    """Lint each work item as one task on the Dask cluster at `scheduler` ("local": one
    started here with `jobs` worker processes), with the collision commands' helper (each
    task in its own process on the worker; a task Dask could not run is a `_Crash`)."""
    # here, not at the top: the Dask client imports asyncio and the task runner
    # multiprocessing, which a warm lint must not pay for
    from robotdesc.collision.cluster import run_tasks_on_cluster
    from robotdesc.collision.worker import TaskFailure

    def crashes_named(outcomes: list[Any]) -> list[Outcome | _Crash]:
        return [_Crash(item[0].name(), f"on the Dask cluster: {o.kind}: {o.message}", "")
                if isinstance(o, TaskFailure) else o for item, o in zip(work, outcomes)]

    if scheduler != "local":
        log.info("linting %d targets on the Dask cluster at %s", len(work), scheduler)
        return crashes_named(run_tasks_on_cluster(
            _lint_task, work, scheduler=scheduler, timeout_s=CLUSTER_TASK_TIMEOUT_S,
            on_done=on_done))
    try:
        import distributed
    except ImportError:
        raise UsageError("--scheduler local needs the optional extra: "
                         'pip install ".[dask]"') from None
    log.info("linting %d targets on a local Dask cluster of %d processes", len(work), jobs)
    with distributed.LocalCluster(  # type: ignore[no-untyped-call]
            n_workers=jobs, threads_per_worker=1, processes=True,
            dashboard_address=None) as cluster:
        return crashes_named(run_tasks_on_cluster(
            _lint_task, work, scheduler=cluster.scheduler_address,
            timeout_s=CLUSTER_TASK_TIMEOUT_S, on_done=on_done))


def _lint_task(item: tuple[Any, ...]) -> Outcome | _Crash:
    """One target's lint as a cluster task (a module-level function: pickled by name)."""
    return _lint_one(*item)


def _lint_one(target: LintTarget, args: dict[str, str], expand_options: ExpandOptions | None,
              select: Sequence[str] | None,
              ignore: tuple[str, ...], keep_exceptions: bool = False) -> Outcome | _Crash:
    """Lint one target; input errors become failures, bugs become `_Crash` in a worker."""
    try:
        result = lint_target(target, args, expand_options, select, ignore)
    except InputError as exc:
        return LintFailure(target.path, exc, target.variant)
    except Exception as exc:  # a bug: let it through here, carry it as text from a worker
        if keep_exceptions:
            raise
        return _Crash(target.name(), f"{type(exc).__name__}: {exc}", traceback.format_exc())
    return dataclasses.replace(result, expanded=None, robot=None)


def lint_target(target: LintTarget, args: Mapping[str, str],
                expand_options: ExpandOptions | None,
                select: Sequence[str] | None, ignore: Sequence[str]) -> LintResult:
    """Lint one target (not asking the result cache) and store its result there; the result
    keeps its expansion and model, and knows its `inputs`.

    Raises:
        InputError: the target could not be expanded or parsed.
    """
    log.info("linting %s", target.name())
    started_ns = time.time_ns()
    package_paths = tuple(getattr(expand_options, "package_paths", ()))
    package_map = tuple(getattr(expand_options, "package_map", ())) \
        + tuple(target.config.packages)
    # the one package lookup of this target: its rules' meshes and its inputs resolve with it
    find_package = package_lookup(os.path.abspath(target.path), package_paths, package_map)
    result = lint_file(target.path, target.config, args={**dict(target.args), **args},
                       expand_options=expand_options, select=select, ignore=ignore,
                       find_package=find_package)
    locator = None if result.robot is None else \
        inputs_locator(result.robot, find_package=find_package)
    inputs = run_inputs(result.target, config_path=result.config_path,
                        expanded=result.expanded, robot=result.robot,
                        package_paths=package_paths, package_map=package_map, locator=locator)
    result = dataclasses.replace(result, variant=target.variant, inputs=inputs)
    result_cache.store(target_key(target, args, expand_options, select, tuple(ignore)),
                       dataclasses.replace(result, expanded=None, robot=None),
                       started_ns=started_ns,
                       env_names=[used.name for used in
                                  getattr(result.expanded, "env_defaults", ())],
                       complete=meshes_resolve(result.robot, package_paths, package_map,
                                               locator=locator))
    return result


def _context() -> Any:
    """Fork when that is safe (no other thread runs: workers start without re-importing),
    else spawn."""
    import multiprocessing

    methods = multiprocessing.get_all_start_methods()
    if "fork" in methods and threading.active_count() == 1:
        return multiprocessing.get_context("fork")
    return multiprocessing.get_context("spawn")
