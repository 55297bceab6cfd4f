"""SIGTERM during collision generation: the workers are stopped, nothing is left running,
no traceback; a worker whose parent is gone ends quietly (no BrokenPipeError traceback)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parents[1]
SRC = TESTS.parent / "src"

SCRIPT = """
import sys
sys.path[:0] = [{tests!r}, {src!r}]
from collision import faults
from robotdesc.collision.worker import run_tasks
try:
    run_tasks(faults.{function}, [{folder!r}] * 2, jobs=2, timeout_s=60)
except KeyboardInterrupt as error:
    sys.stderr.write(f"interrupted: {{type(error).__name__}}\\n")
    sys.exit(130)
"""


def _start(tmp_path: Path, function: str) -> tuple[subprocess.Popen[str], list[int]]:
    script = SCRIPT.format(tests=str(TESTS), src=str(SRC), function=function,
                           folder=str(tmp_path))
    process = subprocess.Popen([sys.executable, "-c", script], stderr=subprocess.PIPE,
                               stdout=subprocess.DEVNULL, text=True)
    deadline = time.monotonic() + 60
    while len(list(tmp_path.glob("*.pid"))) < 2:
        assert time.monotonic() < deadline, "the workers did not start"
        time.sleep(0.1)
    return process, [int(p.stem) for p in tmp_path.glob("*.pid")]


def _alive(pid: int) -> bool:
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    return "\nState:\tZ" not in status


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc").is_dir(), reason="reads /proc")
def test_sigterm_stops_the_workers_without_a_traceback(tmp_path):
    process, workers = _start(tmp_path, "write_pid_and_sleep")
    process.send_signal(signal.SIGTERM)
    _, err = process.communicate(timeout=30)
    assert process.returncode == 130, err
    assert "Traceback" not in err and "interrupted: Terminated" in err
    deadline = time.monotonic() + 10
    while any(_alive(pid) for pid in workers) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not any(_alive(pid) for pid in workers)


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc").is_dir(), reason="reads /proc")
def test_a_worker_outliving_its_parent_ends_quietly(tmp_path):
    process, workers = _start(tmp_path, "write_pid_and_nap")
    os.kill(process.pid, signal.SIGKILL)  # no chance to stop its workers
    _, err = process.communicate(timeout=30)  # EOF: the workers, which share stderr, ended
    assert "Traceback" not in err and "BrokenPipeError" not in err, err
    assert not any(_alive(pid) for pid in workers)
