"""Fixtures of the physics tests (helpers live in sim_support.py)."""

from __future__ import annotations

from .sim_support import erd_options  # noqa: F401  (a pytest fixture)
