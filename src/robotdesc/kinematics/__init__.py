"""Kinematics and dynamics: a Pinocchio model of the robot, facts about it, and checks.

Pinocchio (`pin` on PyPI, which brings the coal collision library) is optional: install it
with `pip install '.[kinematics]'`. The pure helpers (`mirror`, `configuration`; the tree is
`robotdesc.model.tree`) work without it; `build`, `scene` and `info` import it inside the
functions that need it. See docs/kinematics.md.
"""

from robotdesc.kinematics.optional import (
    PINOCCHIO_HINT,
    KinematicsUnavailable,
    import_pinocchio,
    pinocchio_available,
)

__all__ = ["PINOCCHIO_HINT", "KinematicsUnavailable", "import_pinocchio", "pinocchio_available"]
