"""Helpers shared by tests (importable as `support`: pyproject puts tests/ on sys.path)."""

from __future__ import annotations

import sysconfig
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def example_robot_data_dir() -> Path | None:
    """The robots/ folder of the installed example-robot-data, if present."""
    root = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix/share/example-robot-data/robots"
    return root if root.is_dir() else None


def example_robot_urdfs() -> list[Path]:
    """Every URDF shipped by example-robot-data (empty when it is not installed)."""
    root = example_robot_data_dir()
    return sorted(root.rglob("*.urdf")) if root else []
