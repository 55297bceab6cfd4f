import math

import numpy as np
import pytest

pytest.importorskip("pinocchio")

from kinematics.robots import ARM, robot
from robotdesc.kinematics.build import KinematicBuildError, build_model


def test_pinocchio_reason_is_mapped_to_the_joint_line() -> None:
    text = ('<robot name="r">\n<link name="a"/>\n<link name="b"/>\n'
            '<joint name="knee" type="revolute"><parent link="a"/><child link="b"/></joint>\n'
            '</robot>')
    with pytest.raises(KinematicBuildError) as caught:
        build_model(robot(text, "knee.urdf"))
    problem = caught.value.problem
    assert "Joint [knee]" in problem.reason and "does not specify limits" in problem.reason
    assert problem.element == "joint:knee" and problem.where.span.line == 4
    assert problem.from_pinocchio and str(caught.value).startswith("knee.urdf:4:")


def test_a_cycle_is_refused_before_pinocchio_sees_it() -> None:
    loop = ('<robot name="r"><link name="a"/><link name="b"/>'
            '<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>'
            '<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint></robot>')
    with pytest.raises(KinematicBuildError) as caught:
        build_model(robot(loop))
    assert not caught.value.problem.from_pinocchio


def test_model_keeps_mimic_joints_and_converts_continuous_angles() -> None:
    model = build_model(robot(ARM))
    assert model.model.nq == 5 and model.model.nv == 4  # continuous: cos, sin
    q = model.configuration({"shoulder": math.pi / 2, "elbow": 0.25})
    shoulder = model.model.idx_qs[model.model.getJointId("shoulder")]
    assert np.allclose(q[shoulder:shoulder + 2], (0.0, 1.0))
    rows = model.configurations(["elbow", "shoulder"], [[0.25, math.pi / 2]])
    assert np.allclose(rows[0], q)
