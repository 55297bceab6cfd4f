"""Collision work on a Dask cluster (a local one: two worker processes on this machine):
the same results as a local run, crash isolation inside the Dask workers, clear errors."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

distributed = pytest.importorskip("distributed")

import robotdesc
from collision import faults
from collision.conftest import write_urdf
from robotdesc.collision import generate as generate_module
from robotdesc.collision.cluster import run_tasks_on_cluster
from robotdesc.collision.worker import TaskFailure
from robotdesc.errors import UsageError

NOBODY = "tcp://127.0.0.1:1"  # nothing listens on port 1


@pytest.fixture(scope="module")
def scheduler():
    """The address of a local Dask cluster: two worker processes, one thread each."""
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        yield cluster.scheduler_address


def _worker_pids(address: str) -> dict:
    with distributed.Client(address, set_as_default=False) as client:
        return client.run(os.getpid)


def _reports(result):
    return {o.report.link: (o.report.status, o.report.faces_after,
                            [f.code for f in o.report.findings]) for o in result.outcomes}


def test_the_cluster_gives_the_local_results_and_the_cache_stays_local(package, tmp_path,
                                                                       scheduler):
    robot = robotdesc.load(str(write_urdf(package, {"hip": "hip.stl", "leg": "leg.stl"})))
    local = robotdesc.generate_collision(robot, "hull", jobs=2, use_cache=False)
    seen = []
    cache = str(tmp_path / "cache")
    remote = robotdesc.generate_collision(robot, "hull", scheduler=scheduler, cache_dir=cache,
                                          progress=lambda *p: seen.append(p))
    assert _reports(remote) == _reports(local)
    assert [o.report.link for o in remote.outcomes] == ["hip", "leg"]
    assert all(o.written for o in remote.outcomes)
    assert remote.jobs == 2  # the cluster's worker threads
    assert seen[0] == (0, 2, "") and seen[-1][:2] == (2, 2)
    # The cache was filled on this side: a second run needs no cluster at all.
    again = robotdesc.generate_collision(robot, "hull", scheduler=NOBODY, cache_dir=cache)
    assert [o.report.cached for o in again.outcomes] == [True, True]
    assert _reports(again) == _reports(local)


def test_a_segfault_on_a_dask_worker_is_a_finding_and_the_workers_survive(package,
                                                                          monkeypatch,
                                                                          scheduler):
    before = _worker_pids(scheduler)
    urdf = write_urdf(package, {"good": "hip.stl", "bad": "leg.stl"})
    monkeypatch.setattr(generate_module, "LINK_RUNNER", faults.crash_on_bad_link)
    result = robotdesc.generate_collision(robotdesc.load(str(urdf)), "hull",
                                          scheduler=scheduler, use_cache=False)
    reports = _reports(result)
    assert result.outcomes[0].written  # "ok", or "warning" over a PhysX limit
    assert reports["bad"][0] == "failed" and reports["bad"][2] == ["worker-crashed"]
    assert "SIGSEGV" in result.outcomes[1].report.findings[0].message
    assert _worker_pids(scheduler) == before  # the same two Dask worker processes


def test_run_tasks_on_cluster_keeps_order_and_reports_each_task(scheduler):
    done, threads = [], []
    results = run_tasks_on_cluster(faults.square, [1, 2, 3, 4], scheduler=scheduler,
                                   timeout_s=30, on_done=lambda *d: done.append(d),
                                   on_connect=threads.append)
    assert results == [1, 4, 9, 16]
    assert sorted(done) == [(0, 1), (1, 4), (2, 9), (3, 16)]
    assert threads == [2]
    [failure] = run_tasks_on_cluster(faults.raise_error, [0], scheduler=scheduler,
                                     timeout_s=30, on_done=None)
    assert isinstance(failure, TaskFailure) and failure.kind == "exception"
    assert "boom" in failure.message
    [late] = run_tasks_on_cluster(faults.sleep_forever, [0], scheduler=scheduler,
                                  timeout_s=0.5, on_done=None)
    assert isinstance(late, TaskFailure) and late.kind == "timeout"


def test_no_scheduler_is_a_usage_error_naming_the_address():
    with pytest.raises(UsageError, match="127.0.0.1:1"):
        run_tasks_on_cluster(faults.square, [1], scheduler=NOBODY, timeout_s=30,
                             on_done=None, connect_timeout_s=0.5)
    with pytest.raises(UsageError, match="not a Dask scheduler address"):
        run_tasks_on_cluster(faults.square, [1], scheduler="nonsense://x", timeout_s=30,
                             on_done=None)


def test_without_distributed_the_error_says_how_to_install_it(monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)  # import fails as if missing
    with pytest.raises(UsageError, match=r'pip install "\.\[dask\]"'):
        run_tasks_on_cluster(faults.square, [1], scheduler=NOBODY, timeout_s=30,
                             on_done=None)


def test_cli_with_no_scheduler_exits_2_naming_it_and_writes_nothing(package):
    urdf = write_urdf(package, {"hip": "hip.stl"})
    out = package / "collision"
    env = {**os.environ, "DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT": "1s"}
    run = subprocess.run([sys.executable, "-m", "robotdesc", "collision", str(urdf),
                          "--method", "hull", "--out", str(out), "--no-cache",
                          "--scheduler", NOBODY],
                         capture_output=True, text=True, env=env, timeout=120, check=False)
    assert run.returncode == 2, run.stderr
    assert NOBODY in run.stderr
    assert "Traceback" not in run.stderr
    assert not out.exists()
