"""The optional physics backends, MuJoCo and DART: imported only here, only when a simulation
runs."""

from __future__ import annotations

import logging
from types import ModuleType

from robotdesc.errors import SimUnavailable

#: The requirement of the `sim` extra (pyproject: `[project.optional-dependencies] sim`).
MUJOCO_REQUIREMENT = "mujoco>=3.3"
INSTALL_HINT = ('robotdesc sim needs MuJoCo, an optional extra: pip install ".[sim]" '
                f'(or pip install "{MUJOCO_REQUIREMENT}")')


def import_mujoco() -> ModuleType:
    """The `mujoco` module.

    Raises:
        SimUnavailable: MuJoCo is not installed; the message says how to install it.
    """
    try:
        import mujoco
    except ImportError:
        raise SimUnavailable("mujoco", MUJOCO_REQUIREMENT, INSTALL_HINT) from None
    global _QUIETED
    if not _QUIETED:  # MuJoCo's warnings go to logging, not to stderr and MUJOCO_LOG.TXT
        mujoco.set_mju_user_warning(_log_warning)
        _QUIETED = True
    module: ModuleType = mujoco
    return module


_QUIETED = False
_log = logging.getLogger(__name__)


def _log_warning(message: str) -> None:
    _log.debug("mujoco: %s", message.strip())


#: The requirement of the `dart` extra (pyproject: `[project.optional-dependencies] dart`).
DART_REQUIREMENT = "dartpy>=6.14"
DART_INSTALL_HINT = ("robotdesc sim --engine dart needs DART, an optional extra: "
                     "pip install '.[dart]' in robotdesc's clone "
                     f"(or pip install '{DART_REQUIREMENT}')")


def import_dartpy() -> ModuleType:
    """The `dartpy` module.

    Raises:
        SimUnavailable: dartpy is not installed; the message says how to install it.
    """
    try:
        import dartpy
    except ImportError:
        raise SimUnavailable("dart", DART_REQUIREMENT, DART_INSTALL_HINT) from None
    module: ModuleType = dartpy
    return module
