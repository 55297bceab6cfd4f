"""Build the Pinocchio model of a robot, or say why Pinocchio refuses it.

Pinocchio's URDF reader (urdfdom) prints its reason to the C stderr stream and raises a
generic error; the reason is captured and mapped to the element it names (joint or link
in brackets), so a refused model becomes a finding at that element's source line.

`KinematicBuildError` and its `BuildProblem` live in `robotdesc.errors` with every other
error; they are re-exported here, their old home.
"""

from __future__ import annotations

import os
import re
import sys
import tempfile
import threading
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from robotdesc.errors import BuildProblem, KinematicBuildError
from robotdesc.kinematics.optional import import_pinocchio
from robotdesc.kinematics.urdf_text import MeshPath, pinocchio_urdf
from robotdesc.model.elements import Robot
from robotdesc.model.tree import tree_problem

if TYPE_CHECKING:
    from typing_extensions import Self  # typing.Self from Python 3.11

__all__ = ["BuildProblem", "KinematicBuildError", "KinematicModel", "Refusal", "build_model", "build_urdf",
           "explain", "unfit_for_pinocchio"]

_NAMES = re.compile(r"\[([^\]]*)\]")
_CAPTURE_LOCK = threading.Lock()


@dataclass(frozen=True, eq=False)
class KinematicModel:
    """A robot as Pinocchio sees it.

    Attributes:
        robot: the parsed robot.
        model: the `pinocchio.Model` (fixed base; mimic joints kept as ordinary joints, driven
            by robotdesc).
        urdf: the URDF text given to Pinocchio.
    """

    robot: Robot
    model: Any
    urdf: str

    def configuration(self, positions: dict[str, float]) -> Any:
        """Pinocchio's q vector for joint positions by name (rad or m); others neutral.

        A continuous joint (two entries, cos and sin) gets its angle converted.
        """
        import numpy as np

        pin = import_pinocchio()
        q = np.array(pin.neutral(self.model), dtype=float)
        for index in range(1, self.model.njoints):
            name = self.model.names[index]
            if name not in positions:
                continue
            start, size = self.model.idx_qs[index], self.model.nqs[index]
            value = float(positions[name])
            if size == 1:
                q[start] = value
            elif size == 2:
                q[start:start + 2] = (np.cos(value), np.sin(value))
        return q


    def configurations(self, names: list[str], positions: Any) -> Any:
        """Pinocchio q vectors, one row per row of `positions` ((n, len(names)), rad or m)."""
        import numpy as np

        pin = import_pinocchio()
        rows = np.asarray(positions, dtype=float)
        if rows.ndim != 2:  # a flat list of values; a robot without joints has one pose
            rows = rows.reshape(-1, len(names)) if names else np.zeros((1, 0))
        q = np.tile(np.asarray(pin.neutral(self.model), dtype=float), (len(rows), 1))
        for column, name in enumerate(names):
            if not self.model.existJointName(name):
                continue
            index = self.model.getJointId(name)
            start, size = self.model.idx_qs[index], self.model.nqs[index]
            if size == 1:
                q[:, start] = rows[:, column]
            elif size == 2:
                q[:, start] = np.cos(rows[:, column])
                q[:, start + 1] = np.sin(rows[:, column])
        return q


def build_model(robot: Robot, mesh_path: MeshPath = lambda mesh: None) -> KinematicModel:
    """Build the Pinocchio model of `robot`.

    Args:
        robot: the parsed robot.
        mesh_path: resolves `<mesh>` references for the URDF text (`MeshLocator.path`).

    Raises:
        KinematicsUnavailable: Pinocchio is not installed.
        KinematicBuildError: Pinocchio refused the model.
    """
    import_pinocchio("building the kinematic model")
    unfit = unfit_for_pinocchio(robot)
    if unfit is not None:
        raise KinematicBuildError(unfit)
    urdf = pinocchio_urdf(robot, mesh_path)
    model, refusal = build_urdf(urdf)
    if refusal is not None:
        raise KinematicBuildError(explain(robot, refusal.captured, refusal.error))
    return KinematicModel(robot, model, urdf)


def unfit_for_pinocchio(robot: Robot) -> BuildProblem | None:
    """Why robotdesc refuses to give `robot` to Pinocchio at all (links that do not form one
    tree: urdfdom crashes the process on some of these), or None."""
    broken = tree_problem(robot)
    if broken is None:
        return None
    return BuildProblem(broken[0], broken[1], broken[2], from_pinocchio=False)


@dataclass(frozen=True)
class Refusal:
    """Pinocchio's refusal of a URDF text.

    Attributes:
        error: the text of the exception it raised.
        captured: what urdfdom printed meanwhile (its reasons, on lines "Error: ...").
    """

    error: str
    captured: str


def build_urdf(urdf: str) -> tuple[Any, Refusal | None]:
    """Pinocchio's model of a URDF text (fixed base), or None and its refusal.

    Raises:
        KinematicsUnavailable: Pinocchio is not installed.
    """
    pin = import_pinocchio("building the kinematic model")
    error, model = None, None
    with _CAPTURE_LOCK:
        with _StderrCapture() as capture:
            try:
                model = pin.buildModelFromXML(urdf, False)
            except (ValueError, RuntimeError) as exc:
                error = exc
        captured = capture.text
    if error is not None:
        return None, Refusal(str(error), captured)
    return model, None


def explain(robot: Robot, captured: str, fallback: str) -> BuildProblem:
    """The first reason urdfdom printed, mapped to the joint or link it names."""
    reasons = [line.split(":", 1)[1].strip() for line in captured.splitlines()
               if line.strip().startswith("Error:")]
    reason = reasons[0] if reasons else fallback
    for name in _NAMES.findall(reason):
        joint = robot.joint(name)
        if joint is not None:
            return BuildProblem(reason, f"joint:{name}", joint.where)
        link = robot.link(name)
        if link is not None:
            return BuildProblem(reason, f"link:{name}", link.where)
    return BuildProblem(reason)


class _StderrCapture:
    """Redirect the process's file descriptor 2 to a temporary file (C libraries write there)."""

    def __enter__(self) -> Self:
        sys.stderr.flush()
        self.text = ""
        self._file = tempfile.TemporaryFile()
        self._saved = os.dup(2)
        os.dup2(self._file.fileno(), 2)
        return self

    def __exit__(self, *exc: object) -> None:
        os.dup2(self._saved, 2)
        os.close(self._saved)
        self._file.seek(0)
        self.text = self._file.read().decode("utf-8", errors="replace")
        self._file.close()
