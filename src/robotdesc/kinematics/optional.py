"""Pinocchio is an optional dependency: find it, or say how to install it.

`KinematicsUnavailable` and `PINOCCHIO_HINT` live in `robotdesc.errors` with every other
error; they are re-exported here, their old home."""

from __future__ import annotations

import importlib.util
import logging
from types import ModuleType

from robotdesc.errors import PINOCCHIO_HINT, KinematicsUnavailable

__all__ = ["PINOCCHIO_HINT", "KinematicsUnavailable", "import_pinocchio", "pinocchio_available",
           "pinocchio_or_note"]

log = logging.getLogger(__name__)


def pinocchio_available() -> bool:
    """True when `import pinocchio` can succeed (checked without importing it)."""
    return importlib.util.find_spec("pinocchio") is not None


#: The checks already noted as skipped (each is noted once per process).
_NOTED: set[str] = set()


def pinocchio_or_note(what: str) -> bool:
    """True when Pinocchio is importable; otherwise log at info level, shown with -v (once
    per `what`, e.g. a rule code), that `what` is skipped and how to install Pinocchio.
    `robotdesc lint --select K...` warns by itself (commands/lint.py): a default lint
    without the extra stays quiet."""
    if pinocchio_available():
        return True
    if what not in _NOTED:
        _NOTED.add(what)
        log.info("%s skipped: Pinocchio is not installed; %s", what, PINOCCHIO_HINT)
    return False


def import_pinocchio(what: str = "this command") -> ModuleType:
    """Import and return `pinocchio`.

    Raises:
        KinematicsUnavailable: `pin` is not installed.
    """
    try:
        pinocchio = importlib.import_module("pinocchio")
    except ImportError as error:
        raise KinematicsUnavailable(what) from error
    return pinocchio
