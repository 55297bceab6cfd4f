"""Mismatch causes: unit slips, swapped product signs, rotated tensors, mirror partners."""

from __future__ import annotations

import pytest

from robotdesc.inertia.compare import compare_inertia, mirror_partner
from robotdesc.mesh.primitives import box_properties
from robotdesc.model.elements import Inertia, Inertial, Pose

BOX = box_properties(0.1, 0.2, 0.4)  # density 1; at 1 kg: 0.0166667, 0.0141667, 0.0041667


def inertial(ixx, iyy, izz, ixy=0.0, mass=1.0, rpy=(0.0, 0.0, 0.0)) -> Inertial:
    return Inertial(Pose(rpy=rpy), mass, Inertia(ixx, ixy, 0.0, iyy, 0.0, izz))


def test_agreement_has_no_cause() -> None:
    result = compare_inertia(inertial(0.0166667, 0.0141667, 0.00416667), BOX, 0.5)
    assert not result.mismatch(0.5) and result.cause is None


@pytest.mark.parametrize(("factor", "words"), [(1e9, "g*mm^2"), (1e6, "kg*mm^2"),
                                               (1e3, "grams"), (1e-6, "millimetres")])
def test_unit_slips(factor: float, words: str) -> None:
    result = compare_inertia(inertial(0.0166667 * factor, 0.0141667 * factor,
                                      0.00416667 * factor), BOX, 0.5)
    assert result.mismatch(0.5) and words in result.cause


def test_rotated_tensor_is_recognised_and_origin_rpy_is_honoured() -> None:
    swapped = inertial(0.00416667, 0.0141667, 0.0166667)
    assert "rotated frame" in compare_inertia(swapped, BOX, 0.5).cause
    turned = inertial(0.00416667, 0.0141667, 0.0166667, rpy=(0.0, 1.5707963267948966, 0.0))
    assert not compare_inertia(turned, BOX, 0.5).mismatch(0.5)


def test_swapped_product_sign() -> None:
    rod = box_properties(0.05, 0.5, 0.05).transformed(rpy=(0.0, 0.0, 0.7853981633974483))
    result = compare_inertia(inertial(0.0107292, 0.0107292, 0.0210417, ixy=-0.0103125), rod, 0.5)
    assert "sign of ixy" in result.cause


def test_mirror_partner_names() -> None:
    names = {"left_leg", "right_leg", "l_arm", "r_arm", "torso"}
    assert mirror_partner("right_leg", names) == "left_leg"
    assert mirror_partner("l_arm", names) == "r_arm"
    assert mirror_partner("torso", names) is None
