"""One cache switch: `lint --no-cache` (and ROBOTDESC_CACHE_DIR=off) writes nothing under the
cache folder, whichever cache (expansion, meshes, rules) would have."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from linting.test_fix import make_package

from robotdesc.cli import main

ROBOTS = Path(__file__).resolve().parents[2] / "robots"


def _entries(folder: Path) -> list[Path]:
    return sorted(folder.rglob("*"))


def test_no_cache_writes_nothing_and_a_cached_run_does(tmp_path, monkeypatch):
    path = make_package(tmp_path)
    cache = tmp_path / "cache"
    cache.mkdir()
    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", str(cache))
    main(["lint", str(path), "--no-cache"])
    assert _entries(cache) == []
    main(["lint", str(path)])
    assert any(p.name.startswith("meshes-v") for p in cache.iterdir())  # the switch was it


def test_cache_dir_off_writes_nothing(tmp_path, monkeypatch):
    path = make_package(tmp_path)
    home = tmp_path / "home"
    home.mkdir()
    monkeypatch.setenv("HOME", str(home))
    monkeypatch.delenv("XDG_CACHE_HOME", raising=False)
    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", "off")
    main(["lint", str(path)])
    assert _entries(home) == []


@pytest.mark.slow
def test_no_cache_lint_of_the_engineer_writes_nothing(tmp_path, monkeypatch):
    package = tmp_path / "engineer_description"
    shutil.copytree(ROBOTS / "engineer_description", package)
    cache = tmp_path / "cache"
    cache.mkdir()
    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", str(cache))
    assert main(["lint", str(package), "--no-cache"]) == 0
    assert _entries(cache) == []
