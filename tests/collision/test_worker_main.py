"""A script that calls robotdesc at top level, with no `if __name__ == "__main__":` guard,
works: the worker processes never run the caller's main module again."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from collision.conftest import write_urdf

REPO = Path(__file__).resolve().parents[2]

SCRIPT = """
import robotdesc
robot = robotdesc.load({urdf!r})
result = robotdesc.generate_collision(robot, "hull", use_cache=False, jobs=2)
print("RAN", sorted((o.report.link, o.written) for o in result.outcomes))
"""


@pytest.mark.parametrize("as_module", [False, True], ids=["file", "-m module"])
def test_an_unguarded_script_runs_each_link_once(package, tmp_path, as_module):
    urdf = write_urdf(package, {"hip": "hip.stl", "leg": "leg.stl"})
    (tmp_path / "unguarded.py").write_text(SCRIPT.format(urdf=str(urdf)))
    command = [sys.executable, "-m", "unguarded"] if as_module else \
        [sys.executable, str(tmp_path / "unguarded.py")]
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        filter(None, [str(REPO / "src"), os.environ.get("PYTHONPATH")]))}
    done = subprocess.run(command, cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=300, check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.count("RAN") == 1, done.stdout  # the workers did not run it again
    assert "[('hip', True), ('leg', True)]" in done.stdout
    assert "Traceback" not in done.stderr
