"""The type checker runs in the default test run (issue 15): `python -m mypy` with the
configuration in pyproject.toml, strict on the core (source, errors, diagnostics, spatial,
model) and the rules, and no module is excused from it."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]

pytest.importorskip("mypy", reason="mypy comes with the test extra: pip install '.[test]'")


def _mypy() -> dict:
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["mypy"]


def test_mypy_passes(tmp_path: Path) -> None:
    run = subprocess.run([sys.executable, "-m", "mypy", "--cache-dir", str(tmp_path / "cache")],
                         cwd=ROOT, capture_output=True, text=True, timeout=600, check=False)
    assert run.returncode == 0, run.stdout + run.stderr


def test_the_whole_package_is_strict_and_no_module_is_excused() -> None:
    config = _mypy()
    assert config.get("strict") is True and config.get("files") == ["src/robotdesc"]
    overrides = config.get("overrides", [])
    assert not [o for o in overrides if o.get("ignore_errors") or o.get("strict") is False]
