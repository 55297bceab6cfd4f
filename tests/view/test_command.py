"""`robotdesc view` as a user runs it."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from .robots import write_demo_package

REPO = Path(__file__).resolve().parents[2]


def run(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    path = os.pathsep.join(filter(None, [str(REPO / "src"), os.environ.get("PYTHONPATH")]))
    return subprocess.run([sys.executable, "-m", "robotdesc", *args], capture_output=True, check=False,
                          text=True, cwd=cwd, env={**os.environ, "PYTHONPATH": path},
                          timeout=300)


@pytest.fixture
def urdf(tmp_path: Path) -> Path:
    return write_demo_package(tmp_path)


def _document(page: Path) -> dict:
    text = page.read_text(encoding="utf-8")
    return json.loads(re.search(r'id="robotdesc-view-data">(.*?)</script>', text, re.DOTALL).group(1))


def test_view_writes_the_page(urdf: Path, tmp_path: Path) -> None:
    out = tmp_path / "demo.html"
    done = run("view", str(urdf), "-o", str(out), "--q", "shoulder=0.5", "--q", "grip=0.01",
               "--show", "visual,inertia")
    assert done.returncode == 0, done.stderr
    assert re.search(r"wrote .*demo\.html \(\d\.\d\d MB: 4 links, 6 shapes, \d+ links with "
                     r"findings, 1 shapes not shown", done.stderr)
    document = _document(out)
    assert document["configuration"] == {"shoulder": 0.5, "grip": 0.01, "grip_mirror": -0.01}
    assert document["show"]["inertia"] and not document["show"]["collision"]
    assert any(link["findings"] for link in document["links"])
    assert done.stdout == ""


def test_view_without_lint(urdf: Path, tmp_path: Path) -> None:
    out = tmp_path / "demo.html"
    assert run("view", str(urdf), "-o", str(out), "--no-lint").returncode == 0
    assert not any(link["findings"] for link in _document(out)["links"])


@pytest.mark.parametrize("args, message", [
    (["--q", "elbow=1"], "'elbow' is not a joint"),
    (["--q", "shoulder"], "expected JOINT=VALUE"),
    (["--show", "visual,ghosts"], "--show: unknown 'ghosts'"),
    (["--max-faces", "0"], "--max-faces must be at least 1"),
])
def test_bad_arguments_exit_2_with_a_message(urdf: Path, tmp_path: Path, args, message) -> None:
    done = run("view", str(urdf), "-o", str(tmp_path / "x.html"), *args)
    assert done.returncode == 2 and message in done.stderr
    assert "Traceback" not in done.stderr
    assert not (tmp_path / "x.html").exists()


def test_view_refuses_to_overwrite_its_input(urdf: Path) -> None:
    done = run("view", str(urdf), "-o", str(urdf))
    assert done.returncode == 2 and "refusing to write" in done.stderr
