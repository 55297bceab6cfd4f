"""Pinocchio is an optional dependency: find it, or say how to install it."""

from __future__ import annotations

import importlib.util
from types import ModuleType

from robotdesc.errors import InputError

#: What to tell a user who lacks Pinocchio.
PINOCCHIO_HINT = "install it with: pip install '.[kinematics]'  (the `pin` package)"


class KinematicsUnavailable(InputError):
    """Pinocchio (`pin`) is not installed, so kinematic checks cannot run (exit code 2)."""

    def __init__(self, what: str) -> None:
        super().__init__(f"{what} needs Pinocchio, which is not installed; {PINOCCHIO_HINT}")


def pinocchio_available() -> bool:
    """True when `import pinocchio` can succeed (checked without importing it)."""
    return importlib.util.find_spec("pinocchio") is not None


def import_pinocchio(what: str = "this command") -> ModuleType:
    """Import and return `pinocchio`.

    Raises:
        KinematicsUnavailable: `pin` is not installed.
    """
    try:
        import pinocchio
    except ImportError as error:
        raise KinematicsUnavailable(what) from error
    return pinocchio
