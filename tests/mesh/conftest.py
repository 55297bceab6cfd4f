"""Shared fixtures for the mesh tests: tiny meshes written to tmp_path, and the path to
example-robot-data's meshes (tests that need them skip when it is not installed)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from support import example_robot_data_dir

from .builders import box_triangles


@pytest.fixture
def box_soup() -> np.ndarray:
    return box_triangles()


@pytest.fixture(scope="session")
def robots_dir() -> Path:
    """example-robot-data's robots/ directory; skips the test when it is not installed."""
    root = example_robot_data_dir()
    if root is None:
        pytest.skip("example-robot-data is not installed")
    return root
