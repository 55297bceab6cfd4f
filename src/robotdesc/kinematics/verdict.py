"""Whether Pinocchio builds a robot's model, and why not (rule K101), asked of a forked child.

Pinocchio's import costs about 60 ms of CPU (its C++ bindings and coal), ten times the build
of a model. A cold lint that needs no more of Pinocchio than its verdict (`build_problem`)
forks a child while the xacro worker expands and this process has nothing to do
(`start_verdict`): the child imports Pinocchio then, on time that was idle, and waits for the
model (`Verdict.submit`, once parsed: the URDF text Pinocchio is given); this process never
imports Pinocchio. The child answers one JSON object on a pipe, read like a cache entry
(types checked, size capped); a child that fails or answers nonsense only means the model is
built here (`build_model`), as it is without a child.
"""

from __future__ import annotations

import json
import logging
import os
from typing import Literal

from robotdesc.errors import BuildProblem, KinematicBuildError
from robotdesc.forked import Forked, can_fork, read_all, write_all
from robotdesc.kinematics.build import (
    Refusal,
    build_model,
    build_urdf,
    explain,
    unfit_for_pinocchio,
)
from robotdesc.kinematics.optional import import_pinocchio
from robotdesc.kinematics.urdf_text import pinocchio_urdf
from robotdesc.model.elements import Robot

log = logging.getLogger(__name__)

__all__ = ["Verdict", "build_problem", "start_verdict", "verdict_started"]

#: The longest answer read from the child (urdfdom's messages about one model).
_MAX_ANSWER = 1 << 20
#: The longest URDF text the child reads (a model larger than this is built here).
_MAX_URDF = 1 << 30

#: The processes that started a verdict child (`verdict_started`).
_STARTED: set[int] = set()
#: The verdicts being decided (one per linted model at a time).
_PENDING: list[Verdict] = []


class Verdict:
    """Pinocchio's verdict on a model that `submit` gives it, decided by a forked child
    that imports Pinocchio meanwhile.

    Raises:
        OSError: no child could be forked.
    """

    def __init__(self) -> None:
        self.robot: Robot | None = None
        self._child: Forked | None = Forked(_decide)

    def submit(self, robot: Robot) -> None:
        """Give the child `robot` to decide on (once)."""
        if self._child is None or self.robot is not None:
            return
        self.robot = robot
        if unfit_for_pinocchio(robot) is not None:  # refused before Pinocchio is asked
            self.close()
            return
        self._child.send(pinocchio_urdf(robot).encode("utf-8"))

    def answer(self) -> Refusal | Literal["builds"] | None:
        """Pinocchio's refusal of the model, or "builds"; None when the child gave no usable
        answer (the model is to be built here)."""
        if self._child is None or self.robot is None:
            return None
        data = self._child.read_to_end(_MAX_ANSWER)
        self.close()
        try:
            answer = json.loads(data or b"")
            refused = answer["refusal"]
            if refused is None:
                return "builds"
            error, captured = refused["error"], refused["captured"]
            if isinstance(error, str) and isinstance(captured, str):
                return Refusal(error, captured)
        except (ValueError, KeyError, TypeError):
            pass
        log.debug("Pinocchio's verdict from the child: no usable answer (%s bytes)",
                  "too many" if data is None else len(data))
        return None

    def close(self) -> None:
        """End the child (when it still runs) and forget this verdict."""
        if self._child is not None:
            self._child.close()
            self._child = None
        if self in _PENDING:
            _PENDING.remove(self)


def _decide(inbox: int, out: int) -> None:
    """In the child: import Pinocchio, then build the URDF text the inbox brings (nothing:
    no model to decide on) and write the answer."""
    import_pinocchio("building the kinematic model")
    urdf = read_all(inbox, _MAX_URDF)
    if not urdf:
        return
    _, refusal = build_urdf(urdf.decode("utf-8"))
    answer = None if refusal is None else {"error": refusal.error, "captured": refusal.captured}
    write_all(out, json.dumps({"refusal": answer}).encode())


def verdict_started() -> bool:
    """Whether this process has started a verdict child before (a lint of several targets
    in one process imports Pinocchio once, here, after the first)."""
    return os.getpid() in _STARTED


def start_verdict() -> Verdict | None:
    """Fork a child that imports Pinocchio now and decides on the model `submit` gives it
    later (`build_problem` takes the verdict), when this process may fork; else None."""
    if not can_fork():
        return None
    _STARTED.add(os.getpid())
    try:
        verdict = Verdict()
    except OSError as error:
        log.debug("Pinocchio's verdict not decided in a second process: %s", error)
        return None
    _PENDING.append(verdict)
    return verdict


def build_problem(robot: Robot) -> BuildProblem | None:
    """Why Pinocchio (or robotdesc, before it) refuses `robot`; None when the model builds.
    The verdict of a child `start_verdict` started for this robot when it answered, else
    the model is built here.

    Raises:
        KinematicsUnavailable: Pinocchio is not installed (and no child answered).
    """
    unfit = unfit_for_pinocchio(robot)
    if unfit is not None:
        return unfit
    pending = next((verdict for verdict in _PENDING if verdict.robot is robot), None)
    answer = pending.answer() if pending is not None else None
    if answer == "builds":
        return None
    if isinstance(answer, Refusal):
        return explain(robot, answer.captured, answer.error)
    try:
        build_model(robot)
    except KinematicBuildError as error:
        return error.problem
    return None
