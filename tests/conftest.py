"""Shared test setup: caches go to a per-session temporary folder, never to ~/.cache."""

from __future__ import annotations

import os

import pytest


@pytest.fixture(scope="session", autouse=True)
def _isolated_cache(tmp_path_factory: pytest.TempPathFactory) -> None:
    os.environ["ROBOTDESC_CACHE_DIR"] = str(tmp_path_factory.mktemp("robotdesc-cache"))
