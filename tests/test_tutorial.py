"""docs/tutorial.py runs from start to end, offline, and writes its pages."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
TUTORIAL = REPO / "docs" / "tutorial.py"

#: Run the tutorial as `python docs/tutorial.py` does (the main module is its file, which
#: worker processes must not run again), with IP connections refused: a cell that reached
#: for the network fails the test. Unix sockets stay allowed for the workers.
OFFLINE_RUNNER = """
import socket, sys
_connect = socket.socket.connect
def connect(self, address):
    if self.family in (socket.AF_INET, socket.AF_INET6):
        raise OSError("network access in the tutorial: " + repr(address))
    return _connect(self, address)
socket.socket.connect = connect
import runpy
runpy.run_path(sys.argv[1], run_name="__main__")
"""


def test_tutorial_is_a_jupytext_percent_script() -> None:
    text = TUTORIAL.read_text(encoding="utf-8")
    assert "format_name: percent" in text
    assert text.count("# %% [markdown]") >= 5 and text.count("\n# %%\n") >= 6
    compile(text, str(TUTORIAL), "exec")


@pytest.mark.slow
def test_tutorial_runs_offline(tmp_path: Path) -> None:
    path = os.pathsep.join(filter(None, [str(REPO / "src"), os.environ.get("PYTHONPATH")]))
    env = {**os.environ, "PYTHONPATH": path, "ROBOTDESC_TUTORIAL_OUT": str(tmp_path),
           "ROBOTDESC_CACHE_DIR": str(tmp_path / "cache"), "MPLBACKEND": "Agg"}
    done = subprocess.run([sys.executable, "-c", OFFLINE_RUNNER, str(TUTORIAL)],
                          capture_output=True, check=False, text=True, env=env, cwd=tmp_path, timeout=900)
    assert done.returncode == 0, done.stderr[-4000:]
    out = done.stdout
    assert "engineer: 246 links" in out
    assert "0 error, 0 warning, 0 info>" in out  # the bundled description is lint-clean
    assert "left_main_wheel_0_link" in out and " box " in out and "geometry" in out
    assert "head_link" in out and "-> hull" in out
    for page in ("engineer.html", "report.html"):
        text = (tmp_path / page).read_text(encoding="utf-8")
        assert text.startswith("<!DOCTYPE html>") and "data-robotdesc-scene" in text
    assert "Generated collision geometry" in (tmp_path / "report.html").read_text("utf-8")
