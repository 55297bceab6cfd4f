"""Mesh summaries made by this process and a forked child together (mesh/prefetch.py): the
same summaries and errors as one process makes, whatever the child does."""

from __future__ import annotations

import os
import sys
import threading
from collections.abc import Sequence
from pathlib import Path

import pytest

from robotdesc.forked import can_fork
from robotdesc.mesh.analyze import summarize_file
from robotdesc.mesh.errors import DEFAULT_LIMITS, MeshError, MeshLimits
from robotdesc.mesh.prefetch import Prefetch
from robotdesc.mesh.records import MeshSummary

from .builders import box_triangles, write_binary_stl

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="forks only on Linux")


def _jobs(tmp_path: Path) -> list[tuple[str, tuple[float, ...]]]:
    jobs = []
    for number in range(6):
        path = write_binary_stl(tmp_path / f"box{number}.stl",
                                box_triangles((1.0 + number, 2.0, 3.0)))
        jobs.append((str(path), (1.0, 1.0, 1.0 + number)))
    broken = tmp_path / "broken.stl"
    broken.write_bytes(b"\x00" * 100)
    jobs.insert(2, (str(broken), (1.0, 1.0, 1.0)))
    return jobs


def _alone(job: tuple[str, tuple[float, ...]]) -> MeshSummary | MeshError:
    try:
        return summarize_file(job[0], job[1], DEFAULT_LIMITS)
    except MeshError as error:
        return error


def _same(found: MeshSummary | MeshError | None, expected: MeshSummary | MeshError) -> bool:
    if isinstance(expected, MeshError):
        return isinstance(found, MeshError) and (found.kind, found.detail, found.path) \
            == (expected.kind, expected.detail, expected.path)
    return found == expected


def test_two_processes_give_the_summaries_one_gives(tmp_path: Path) -> None:
    jobs = _jobs(tmp_path)
    ahead = Prefetch(jobs, DEFAULT_LIMITS, summarize_file)
    try:
        assert all(_same(ahead.take(*job), _alone(job)) for job in jobs)
        assert ahead.take(str(tmp_path / "other.stl"), (1.0, 1.0, 1.0)) is None
    finally:
        ahead.close()


def test_a_job_the_child_fails_on_or_leaves_is_summarized_here(tmp_path: Path) -> None:
    jobs = _jobs(tmp_path)
    parent = os.getpid()

    def failing_in_the_child(path: str, scale: Sequence[float],
                             limits: MeshLimits) -> MeshSummary:
        if os.getpid() != parent:
            if path.endswith("box5.stl"):
                raise RuntimeError("a bug")
            if path.endswith("box4.stl"):
                os._exit(0)  # the child ends before the rest
        return summarize_file(path, scale, limits)

    ahead = Prefetch(jobs, DEFAULT_LIMITS, failing_in_the_child)
    try:
        answers = [ahead.take(*job) for job in jobs]
    finally:
        ahead.close()
    for job, answer in zip(jobs, answers):  # None: the caller summarizes it
        assert answer is None or _same(answer, _alone(job))
    assert answers[-1] is None or _same(answers[-1], _alone(jobs[-1]))


@pytest.mark.parametrize("answer", [
    b'{"job": 99, "summary": {}}',  # a job that does not exist
    b'{"job": 0, "summary": {"method": "exact"}}',  # not a summary's shape
    b'{"job": 0, "error": {"kind": "no-such-kind", "detail": "x"}}',
])
def test_an_answer_the_child_does_not_write_ends_it(tmp_path: Path, answer: bytes) -> None:
    jobs = _jobs(tmp_path)
    ahead = Prefetch(jobs, DEFAULT_LIMITS, summarize_file)
    try:
        ahead._record(answer)  # what a broken child would write
        assert ahead._child is None  # ended and reaped
        assert all(_same(ahead.take(*job), _alone(job)) for job in jobs)  # all here
    finally:
        ahead.close()


def test_no_fork_while_another_thread_runs(monkeypatch: pytest.MonkeyPatch) -> None:
    """Only threads that draw progress may run while the child is forked (a lock another
    thread holds, in code the child runs, would stay held in the child)."""
    stop = threading.Event()
    other = threading.Thread(target=stop.wait, name="a-dask-worker-thread", daemon=True)
    progress = threading.Thread(target=stop.wait, name="robotdesc-progress-lint", daemon=True)
    here = threading.current_thread()
    monkeypatch.setattr(threading, "enumerate", lambda: [here, progress])
    assert can_fork()
    monkeypatch.setattr(threading, "enumerate", lambda: [here, progress, other])
    assert not can_fork()
