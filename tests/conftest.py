"""Shared test setup: caches go to a per-session temporary folder, never to ~/.cache."""

from __future__ import annotations

import os
import sysconfig
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="session", autouse=True)
def _isolated_cache(tmp_path_factory: pytest.TempPathFactory) -> None:
    os.environ["ROBOTDESC_CACHE_DIR"] = str(tmp_path_factory.mktemp("robotdesc-cache"))


def example_robot_data_dir() -> Path | None:
    """The robots/ folder of the installed example-robot-data, if present."""
    root = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix/share/example-robot-data/robots"
    return root if root.is_dir() else None


def example_robot_urdfs() -> list[Path]:
    root = example_robot_data_dir()
    return sorted(root.rglob("*.urdf")) if root else []
