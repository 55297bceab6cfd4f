"""Pinocchio's verdict from a forked child (robotdesc/kinematics/verdict.py): the same problem
as a build here, for a model Pinocchio refuses and one it builds; a child that answers
nonsense, ends early or is given nothing only means the model is built here."""

from __future__ import annotations

import os

import pytest

pytest.importorskip("pinocchio", reason="Pinocchio is the optional [kinematics] extra")

from kinematics.robots import ARM, robot
from robotdesc.forked import forks_here
from robotdesc.kinematics import verdict as verdicts
from robotdesc.kinematics.build import KinematicBuildError, build_model
from robotdesc.kinematics.verdict import Verdict, build_problem, start_verdict

pytestmark = pytest.mark.skipif(not forks_here(),
                                 reason="robotdesc forks helper processes on Linux only")

KNEE = ('<robot name="r">\n<link name="a"/>\n<link name="b"/>\n'
        '<joint name="knee" type="revolute"><parent link="a"/><child link="b"/></joint>\n'
        '</robot>')
LOOP = ('<robot name="r"><link name="a"/><link name="b"/>'
        '<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>'
        '<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint></robot>')


def _here(text: str) -> object:
    try:
        build_model(robot(text, "knee.urdf"))
    except KinematicBuildError as error:
        return error.problem
    return None


@pytest.mark.parametrize("text", [KNEE, ARM, LOOP])
def test_the_childs_verdict_is_the_build_here(text: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(verdicts, "can_fork", lambda: True)  # a test run may hold threads
    model = robot(text, "knee.urdf")
    verdict = start_verdict()
    assert verdict is not None
    try:
        verdict.submit(model)
        assert build_problem(model) == _here(text)
    finally:
        verdict.close()
    assert not verdicts._PENDING


def test_a_child_that_answers_nonsense_means_a_build_here(
        monkeypatch: pytest.MonkeyPatch) -> None:
    def nonsense(_inbox: int, out: int) -> None:
        os.write(out, b'{"refusal": {"error": 3}}')

    monkeypatch.setattr(verdicts, "_decide", nonsense)
    model = robot(KNEE, "knee.urdf")
    verdict = Verdict()
    verdicts._PENDING.append(verdict)
    verdict.submit(model)
    assert verdict.answer() is None  # unreadable: no verdict
    verdict = Verdict()
    verdicts._PENDING.append(verdict)
    verdict.submit(model)
    problem = build_problem(model)  # built here
    assert problem is not None and problem.element == "joint:knee"
    assert not verdicts._PENDING


def test_a_child_that_ends_early_or_is_given_nothing(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(verdicts, "_decide", lambda _inbox, _out: None)
    model = robot(ARM)
    verdict = Verdict()
    verdict.submit(model)
    assert verdict.answer() is None
    idle = Verdict()  # never given a model: closed without an answer
    assert idle.answer() is None
    idle.close()


def test_no_child_where_this_process_may_not_fork(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(verdicts, "can_fork", lambda: False)
    assert start_verdict() is None
    model = robot(KNEE, "knee.urdf")
    problem = build_problem(model)  # built here
    assert problem is not None and problem.element == "joint:knee"
