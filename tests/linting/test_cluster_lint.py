"""`robotdesc lint --scheduler`: targets linted on a Dask cluster (a local one here) give the
findings and failures of a local run, in target order, with progress."""

from __future__ import annotations

from pathlib import Path

import pytest

distributed = pytest.importorskip("distributed")

from robotdesc.cli import main  # noqa: E402
from robotdesc.errors import UsageError  # noqa: E402
from robotdesc.expansion import ExpandOptions  # noqa: E402
from robotdesc.linting.parallel import lint_targets  # noqa: E402
from robotdesc.linting.result import LintFailure  # noqa: E402
from robotdesc.linting.targets import LintTarget, discover_targets  # noqa: E402

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures"
ENGINEER = Path(__file__).resolve().parents[2] / "robots" / "engineer_description"


def _summary(outcomes: list) -> list:
    return [(type(o).__name__, o.target, o.variant,
             str(o.error) if isinstance(o, LintFailure) else
             [(d.code, d.element, d.message, str(d.where.span) if d.where else "")
              for d in o.diagnostics])
            for o in outcomes]


@pytest.fixture(scope="module")
def scheduler():
    """A local Dask cluster in this process: one worker thread pool (each task still runs
    in its own process, as on a real cluster)."""
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                  dashboard_address=None) as cluster:
        yield cluster.scheduler_address


def test_the_cluster_gives_the_local_findings(tmp_path: Path, scheduler: str) -> None:
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot name='b'><link name='a'></robot>")
    targets = [*discover_targets(str(FIXTURES / "ci_workspace")).targets,
               *discover_targets(str(FIXTURES / "macro_twice")).targets,
               LintTarget(str(broken))]
    options = ExpandOptions(use_cache=False)
    local = lint_targets(targets, expand_options=options)
    done: list[int] = []
    remote = lint_targets(targets, expand_options=options, scheduler=scheduler,
                          on_done=done.append)
    assert _summary(remote) == _summary(local)
    assert any(isinstance(o, LintFailure) for o in remote)
    assert done[-1] == len(targets)


@pytest.mark.slow
def test_the_engineer_on_the_cluster_matches_the_local_run(scheduler: str) -> None:
    targets = list(discover_targets(str(ENGINEER)).targets)
    options = ExpandOptions(use_cache=False)
    assert _summary(lint_targets(targets, expand_options=options, scheduler=scheduler)) \
        == _summary(lint_targets(targets, expand_options=options))


def test_a_scheduler_that_does_not_answer_is_a_usage_error(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import dask

    robot = tmp_path / "r.urdf"
    robot.write_text("<robot name='r'><link name='a'/></robot>")
    with dask.config.set({"distributed.comm.timeouts.connect": "2s"}), pytest.raises(UsageError, match="cannot reach the Dask scheduler"):
        lint_targets([LintTarget(str(robot))], expand_options=ExpandOptions(use_cache=False),
                     scheduler="tcp://127.0.0.1:1")
    with dask.config.set({"distributed.comm.timeouts.connect": "2s"}):
        assert main(["lint", "-q", "--no-cache", "--scheduler", "tcp://127.0.0.1:1",
                     str(robot)]) == 2
    assert "cannot reach the Dask scheduler at tcp://127.0.0.1:1" in capsys.readouterr().err
