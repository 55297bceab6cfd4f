"""Shared test setup: caches go to a per-session temporary folder, never to ~/.cache; in CI
the test extra must be complete."""

from __future__ import annotations

import os

import pytest


@pytest.fixture(scope="session", autouse=True)
def _isolated_cache(tmp_path_factory: pytest.TempPathFactory) -> None:
    os.environ["ROBOTDESC_CACHE_DIR"] = str(tmp_path_factory.mktemp("robotdesc-cache"))


#: What the test extra installs and some tests skip without (for a run without the extra).
TEST_EXTRA_MODULES = ("distributed", "pinocchio", "mujoco", "jsonschema")


def pytest_sessionstart(session: pytest.Session) -> None:
    """In CI (`CI` set), the README's command has installed the test extra: there a missing
    part of it is an error, not a silent skip of the tests that need it."""
    import importlib.util

    from support import example_robot_data_dir

    if not os.environ.get("CI"):
        return
    missing = [name for name in TEST_EXTRA_MODULES if importlib.util.find_spec(name) is None]
    if example_robot_data_dir() is None:
        missing.append("example-robot-data")
    if missing:
        raise pytest.UsageError(f"CI: the test extra is incomplete, missing {', '.join(missing)}"
                                " (python -m pip install -e \".[test]\")")
