"""`generate_collision`: new collision geometry for every link with meshes, measured.

Pipeline per link: resolve its meshes (visual by default) -> hash the sources and the
parameters -> serve from the cache, or load and validate the meshes and run the method in an
isolated worker (see worker.py; on a Dask cluster, cluster.py) -> check the engine limits.
A link that fails (unreadable mesh, no volume, worker crash or timeout, broken result) is a
finding for that link; the others complete. The input robot is never modified.
"""

from __future__ import annotations

import logging
import time
from collections import Counter
from dataclasses import replace
from typing import Any, Callable, Sequence

from robotdesc.collision.cache import CACHE_VERSION, CollisionCache
from robotdesc.collision.choose import choose_auto, left_out, no_contact_outcome
from robotdesc.collision.limits import limit_findings
from robotdesc.collision.link import LinkTask, run_link
from robotdesc.collision.methods import DEFAULT_METHOD
from robotdesc.collision.options import CollisionOptions
from robotdesc.collision.result import CollisionResult, Finding, LinkOutcome, LinkReport
from robotdesc.collision.sources import (
    LinkSources,
    link_sources,
    load_link_soup,
    sources_digest,
)
from robotdesc.collision.worker import TaskFailure, default_jobs, run_tasks, start_workers_early
from robotdesc.digest import file_digest
from robotdesc.errors import InputError, UnknownLinkError
from robotdesc.mesh.cache import MeshCache, default_cache_dir
from robotdesc.mesh.locate import MeshLocator
from robotdesc.model.elements import Robot

log = logging.getLogger(__name__)

#: The function each worker runs on a `LinkTask` (module level, so tests may replace it to
#: inject a crash).
LINK_RUNNER: Callable[[LinkTask], LinkOutcome] = run_link

Progress = Callable[[int, int, str], None]


def generate_collision(robot: Robot, method: str = DEFAULT_METHOD, *,
                       options: CollisionOptions | None = None,
                       package_paths: Sequence[str] = (),
                       package_map: Sequence[tuple[str, str]] = (),
                       links: Sequence[str] | None = None, jobs: int | None = None,
                       use_cache: bool = True, cache_dir: str | None = None,
                       progress: Progress | None = None, scheduler: str | None = None,
                       allow_absolute_paths: bool = False,
                       **overrides: Any) -> CollisionResult:
    """Make collision geometry for a robot's links and measure it.

    Args:
        robot: a parsed robot (`robotdesc.load`); not modified.
        method: "auto" (default), "decimate", "hull", "coacd" or "primitive" (the table:
            `robotdesc.collision.methods`).
        options: every parameter (see `CollisionOptions`); `method` and `overrides`
            (option names, e.g. `ratio=0.05`, `threshold=0.08`) replace its fields.
        package_paths, package_map: where `package://` meshes are looked up first.
        links: only these links (default: every link with geometry).
        jobs: worker processes (default: all cores); ignored with `scheduler`.
        use_cache: reuse results of unchanged links.
        cache_dir: the cache root (default: $ROBOTDESC_CACHE_DIR or ~/.cache/robotdesc).
        progress: called with (links done, links in all, link name) as links finish.
        scheduler: the address of a Dask scheduler (e.g. "tcp://host:8786"): the links
            run on that cluster, each still in its own process on a Dask worker (needs
            `robotdesc[dask]`; links served from the cache never reach the cluster).
        allow_absolute_paths: accept `file://` and absolute mesh paths (as the config's
            `[meshes] allow_absolute_paths` for lint); off: such a mesh, like one reached
            through `../` or a symlink out of its package, fails its link unread.

    Returns:
        Per link: the new geometry and a report (faces, hulls, volume ratio, distances).

    Raises:
        CollisionOptionError: an option is out of range or unknown (a `UsageError`).
        UnknownLinkError: a link named in `links` does not exist (a `UsageError`).
        UsageError: `scheduler` is set but unreachable, or `distributed` is missing.
    """
    started = time.perf_counter()
    options = replace(options or CollisionOptions(), method=method, **overrides).validated()
    plan = plan_links(robot, options, package_paths, package_map, links, use_cache,
                      cache_dir, allow_absolute_paths)
    total = len(plan.sources)
    outcomes: dict[int, LinkOutcome] = {}
    tasks: list[tuple[int, LinkTask]] = []
    first_with_key: dict[str, int] = {}   # links with the same sources are made once
    copies: dict[int, int] = {}
    for index, (sources, key) in enumerate(zip(plan.sources, plan.keys)):
        hit = plan.cache.get(key) if plan.cache is not None and key else None
        if hit is not None:
            outcomes[index] = replace(hit, report=replace(hit.report, link=sources.link,
                                                          cached=True))
            continue
        if key and key in first_with_key:
            copies[index] = first_with_key[key]
            continue
        if key:
            first_with_key[key] = index
        if scheduler is None and not tasks:
            start_workers_early()  # its imports overlap the loading of the meshes
        failure = None if not sources.problems else Finding(
            "mesh-unresolved", "error", "; ".join(sources.problems))
        if failure is None:
            try:
                soup = load_link_soup(sources)
            except (InputError, ValueError, OSError) as error:  # MeshError is an InputError
                failure = Finding("mesh-error", "error", str(error))
        if failure is not None:
            outcomes[index] = _failed(sources.link, options.method, key, failure)
            continue
        tasks.append((index, LinkTask(sources.link, soup, options, key or "")))
    # largest first: the longest links start at once, the small ones fill in after
    tasks.sort(key=lambda item: -len(item[1].triangles))
    copied = Counter(copies.values())
    done = len(outcomes)
    if progress is not None:
        progress(done, total, "")
    jobs = max(1, jobs or default_jobs())
    work = [len(task.triangles) for _, task in tasks]
    work_done = 0
    work_started = time.perf_counter()

    def finished(position: int, outcome: object) -> None:
        """Cache the link at once (an interrupted run keeps it); count it and its
        identical copies; estimate the time left by the triangles still to process."""
        nonlocal done, work_done
        index, task = tasks[position]
        if plan.cache is not None and isinstance(outcome, LinkOutcome) and outcome.written:
            plan.cache.put(replace(outcome, key=task.key))
        done += 1 + copied[index]
        work_done += work[position]
        if progress is not None:
            left = sum(work) - work_done
            eta = "" if not left else "; about " + _duration(
                (time.perf_counter() - work_started) * left / max(work_done, 1)) + " left"
            progress(done, total, task.link + eta)

    arguments = [task for _, task in tasks]
    if not tasks:
        results: list[Any] = []
    elif scheduler is not None:
        from robotdesc.collision.cluster import run_tasks_on_cluster

        def connected(threads: int) -> None:
            nonlocal jobs
            jobs = max(1, threads)

        results = run_tasks_on_cluster(LINK_RUNNER, arguments, scheduler=scheduler,
                                       timeout_s=options.mesh_timeout_s, on_done=finished,
                                       on_connect=connected)
    else:
        results = run_tasks(LINK_RUNNER, arguments, jobs=jobs,
                            timeout_s=options.mesh_timeout_s, on_done=finished)
    for (index, task), outcome in zip(tasks, results):
        if isinstance(outcome, TaskFailure):
            code = {"crashed": "worker-crashed", "timeout": "worker-timeout"}.get(
                outcome.kind, "worker-error")
            outcome = _failed(task.link, options.method, task.key,
                              Finding(code, "error", _failure_message(task.link, outcome,
                                                                      options)))
        outcomes[index] = replace(outcome, key=task.key)
    for index, original in copies.items():
        made = outcomes[original]
        outcomes[index] = replace(made, report=replace(
            made.report, link=plan.sources[index].link, cached=made.written))
    if progress is not None and done < total:  # copies of links that failed to load
        progress(total, total, "")
    ordered = tuple(outcomes[i] for i in range(total))
    ordered = _auto_choice(ordered, options) if options.method == "auto" \
        else tuple(_with_limits(o, options) for o in ordered)
    return CollisionResult(robot, ordered, options, time.perf_counter() - started, jobs)


class Plan:
    """The links to process, their sources, and their keys (no mesh is loaded)."""

    def __init__(self, sources: list[LinkSources], keys: list[str | None],
                 cache: CollisionCache | None) -> None:
        self.sources = sources
        self.keys = keys
        self.cache = cache


def plan_links(robot: Robot, options: CollisionOptions, package_paths: Sequence[str] = (),
               package_map: Sequence[tuple[str, str]] = (),
               links: Sequence[str] | None = None, use_cache: bool = True,
               cache_dir: str | None = None, allow_absolute_paths: bool = False) -> Plan:
    """Resolve each link's sources (under the package rules of lint, see sources.py) and
    compute its key (used by generation and --check).

    Raises:
        UnknownLinkError: a link named in `links` has no geometry of `options.source`.
    """

    found = link_sources(robot, options.source,
                         MeshLocator.for_robot(robot, package_paths, package_map,
                                               allow_absolute=allow_absolute_paths))
    if links is not None:
        known = {s.link for s in found}
        missing = [name for name in links if name not in known]
        if missing:
            raise UnknownLinkError(tuple(missing), f"no link with {options.source} geometry "
                                                   f"named {', '.join(missing)}")
        found = [s for s in found if s.link in set(links)]
    root = cache_dir or (default_cache_dir() if use_cache else None)
    mesh_cache = MeshCache(root) if root else None
    digest = mesh_cache.content_digest if mesh_cache is not None else file_digest
    parameters = {**options.key_fields(), "format": CACHE_VERSION}
    keys = [sources_digest(s, digest, parameters) for s in found]
    return Plan(found, keys, CollisionCache(root) if (root and use_cache) else None)


def _auto_choice(outcomes: tuple[LinkOutcome, ...],
                 options: CollisionOptions) -> tuple[LinkOutcome, ...]:
    """Method auto: links left out of contact on request, then the robot-wide choice under
    the tolerance and the triangle budget (choose.py), engine limits checked on the result."""
    out = left_out([o.report.link for o in outcomes], options.no_contact)
    kept = tuple(no_contact_outcome(o) if o.report.link in out else o for o in outcomes)
    return tuple(_with_limits(o, options) for o in choose_auto(kept, options))


def _with_limits(outcome: LinkOutcome, options: CollisionOptions) -> LinkOutcome:
    if not outcome.written:
        return outcome
    extra = limit_findings(outcome.parts, options.limits)
    if not extra:
        return outcome
    report = outcome.report
    status = "failed" if report.status == "failed" else "warning"
    return replace(outcome, report=replace(report, status=status,
                                           findings=report.findings + extra))


def _failure_message(link: str, failure: TaskFailure, options: CollisionOptions) -> str:
    """What a worker's failure means for `link`; a timeout names `--mesh-timeout`."""
    if failure.kind != "timeout":
        return failure.message
    limit = options.mesh_timeout_s
    hint = ("or a larger --threshold / smaller --coacd-input-faces for a faster CoACD"
            if options.method in ("coacd", "auto") else "or another --method")
    return (f"link {link} did not finish within the per-link limit of {limit:g} s and was "
            f"stopped: raise it with --mesh-timeout {_round_limit(2 * limit)} "
            f"(mesh_timeout_s in Python), {hint}")


def _duration(seconds: float) -> str:
    """`1 min 05 s`, `42 s`."""
    whole = int(seconds + 0.5)
    return f"{whole // 60} min {whole % 60:02d} s" if whole >= 60 else f"{whole} s"


def _round_limit(seconds: float) -> str:
    return f"{max(1, round(seconds)):d}"


def _failed(link: str, method: str, key: str | None, finding: Finding) -> LinkOutcome:
    return LinkOutcome(LinkReport(link, method, "failed", findings=(finding,)), (), key or "")
