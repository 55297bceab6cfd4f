"""MuJoCo, the optional physics backend: imported only here, only when a simulation runs."""

from __future__ import annotations

import logging
from types import ModuleType

from robotdesc.errors import InputError

#: The requirement of the `sim` extra (pyproject: `[project.optional-dependencies] sim`).
MUJOCO_REQUIREMENT = "mujoco>=3.3"
INSTALL_HINT = ('robotdesc sim needs MuJoCo, an optional extra: pip install "robotdesc[sim]" '
                f'(or pip install "{MUJOCO_REQUIREMENT}")')


class SimUnavailable(InputError):
    """MuJoCo is not installed, so the physics checks cannot run."""


def import_mujoco() -> ModuleType:
    """The `mujoco` module.

    Raises:
        SimUnavailable: MuJoCo is not installed; the message says how to install it.
    """
    try:
        import mujoco
    except ImportError:
        raise SimUnavailable(INSTALL_HINT) from None
    global _QUIETED
    if not _QUIETED:  # MuJoCo's warnings go to logging, not to stderr and MUJOCO_LOG.TXT
        mujoco.set_mju_user_warning(_log_warning)
        _QUIETED = True
    return mujoco


_QUIETED = False
_log = logging.getLogger(__name__)


def _log_warning(message: str) -> None:
    _log.debug("mujoco: %s", message.strip())
