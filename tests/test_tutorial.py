"""docs/tutorial.py runs from start to end, offline, and writes its pages."""

from __future__ import annotations

import importlib.util
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

OFFLINE_GUARD = """
import socket
_connect = socket.socket.connect
def connect(self, address):
    if self.family in (socket.AF_INET, socket.AF_INET6):
        raise OSError("network access in the tutorial: " + repr(address))
    return _connect(self, address)
socket.socket.connect = connect
"""

REPO = Path(__file__).resolve().parents[1]
TUTORIAL = REPO / "docs" / "tutorial.py"
NOTEBOOK = REPO / "docs" / "tutorial.ipynb"
CONVERTER = REPO / "scripts" / "tutorial_notebook.py"

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
                          capture_output=True, check=False, text=True, env=env, cwd=tmp_path,
                          timeout=900)
    assert done.returncode == 0, done.stderr[-4000:]
    out = done.stdout
    assert "engineer: 246 links" in out
    assert "0 error, 0 warning, 0 info>" in out  # the bundled description is lint-clean
    assert " box " in out and "geometry" in out
    assert "head_link" in out and "-> hull" in out
    for page in ("engineer.html", "report.html"):
        text = (tmp_path / page).read_text(encoding="utf-8")
        assert text.startswith("<!DOCTYPE html>") and "data-robotdesc-scene" in text
    assert "Generated collision geometry" in (tmp_path / "report.html").read_text("utf-8")


def _converter():
    """scripts/tutorial_notebook.py as a module."""
    spec = importlib.util.spec_from_file_location("tutorial_notebook", CONVERTER)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def notebook_cells(text: str) -> list[tuple[str, str]]:
    """The cells of a percent script as (kind, source), as the converter reads them."""
    return _converter().percent_cells(text)


def test_the_notebook_is_generated_from_the_script_without_outputs() -> None:
    nbformat = pytest.importorskip("nbformat")
    converter = _converter()
    assert NOTEBOOK.read_text(encoding="utf-8") == converter.notebook_json(
        TUTORIAL.read_text(encoding="utf-8")), "run: python scripts/tutorial_notebook.py"
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    nbformat.validate(notebook)
    assert all(not cell.get("outputs") for cell in notebook.cells)
    assert [(c.cell_type, c.source) for c in notebook.cells] == notebook_cells(
        TUTORIAL.read_text(encoding="utf-8"))


def test_tutorial_cells_use_public_api_only() -> None:
    code = "\n".join(source for kind, source in notebook_cells(TUTORIAL.read_text("utf-8"))
                     if kind == "code")
    assert "import robotdesc" in code
    assert "from robotdesc" not in code and "import robotdesc." not in code
    import re

    import robotdesc

    used = set(re.findall(r"robotdesc\.([A-Za-z_]\w*)", code))
    assert used and used <= set(robotdesc.__all__), used - set(robotdesc.__all__)


@pytest.mark.slow
def test_tutorial_runs_as_a_notebook(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    notebook = nbformat.read(NOTEBOOK, as_version=4)  # the shipped notebook
    assert len(notebook.cells) >= 10
    notebook.cells.insert(0, nbformat.v4.new_code_cell(OFFLINE_GUARD))
    elsewhere = tmp_path / "elsewhere"  # not the repository: no bare StopIteration
    elsewhere.mkdir()
    for name, value in {"ROBOTDESC_TUTORIAL_OUT": str(tmp_path / "out"),
                        "ROBOTDESC_CACHE_DIR": str(tmp_path / "cache"), "MPLBACKEND": "Agg",
                        "PYTHONPATH": os.pathsep.join(filter(None, [
                            str(REPO / "src"), os.environ.get("PYTHONPATH")]))}.items():
        monkeypatch.setenv(name, value)
    client = nbclient.NotebookClient(notebook, timeout=900, kernel_name="python3",
                                     resources={"metadata": {"path": str(elsewhere)}})
    client.execute()
    weight = len(json.dumps(nbformat.from_dict(notebook)))
    assert weight < 700_000, f"the executed notebook weighs {weight:,} bytes"

    def outputs(cell) -> str:
        parts = []
        for output in cell.get("outputs", []):
            parts.append(output.get("text", ""))
            parts.extend(str(v) for v in output.get("data", {}).values())
        return "\n".join(parts)

    everything = "\n".join(outputs(cell) for cell in notebook.cells)
    assert "engineer: 246 links" in everything
    summary = next(outputs(cell) for cell in notebook.cells
                   if "robotdesc-robot" in outputs(cell))
    assert len(summary) < 20_000 and "DoF" in summary and "base_footprint" in summary
    assert "_rd_src" not in (tmp_path / "out" / "engineer.urdf").read_text("utf-8")
    assert "0 error, 0 warning, 0 info>" in everything
    assert " box " in everything and "-> hull" in everything
    assert "Generated collision geometry" in (tmp_path / "out" / "report.html").read_text("utf-8")
