import pytest

from robotdesc.kinematics.mirror import mirror_pairs, mirrored_name


@pytest.mark.parametrize(("name", "other"), [
    ("left_arm", "right_arm"), ("panda_leftfinger", "panda_rightfinger"), ("l_hip", "r_hip"),
    ("knee_l", "knee_r"), ("LeftFoot", "RightFoot"), ("leg_L_1", "leg_R_1"),
    ("base", None), ("left_to_right", None), ("l_r", None), ("elbow", None)])
def test_mirrored_name(name: str, other: str | None) -> None:
    assert mirrored_name(name) == other


def test_pairs_exist_on_both_sides_only() -> None:
    assert mirror_pairs(["l_hip", "r_hip", "l_knee", "torso"]) == [("l_hip", "r_hip")]
