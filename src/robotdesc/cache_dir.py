"""Where robotdesc keeps its caches: $ROBOTDESC_CACHE_DIR, else $XDG_CACHE_HOME/robotdesc,
else ~/.cache/robotdesc."""

from __future__ import annotations

import os
from pathlib import Path


def default_cache_dir() -> Path:
    """The cache root (not created here)."""
    explicit = os.environ.get("ROBOTDESC_CACHE_DIR")
    if explicit:
        return Path(explicit)
    xdg = os.environ.get("XDG_CACHE_HOME")
    return (Path(xdg) if xdg else Path.home() / ".cache") / "robotdesc"
