import numpy as np
from kinematics.robots import ARM, robot

from robotdesc.srdf.sampling import sample_positions


def test_samples_stay_within_limits_and_mimics_follow() -> None:
    names, q = sample_positions(robot(ARM), 2000, seed=3)
    assert names == ["shoulder", "elbow", "hand_joint", "hand_twin"]
    column = dict(zip(names, q.T))
    assert column["elbow"].min() >= -0.5 and column["elbow"].max() <= 0.5
    assert column["shoulder"].min() >= -np.pi and column["shoulder"].max() <= np.pi
    assert np.allclose(column["hand_twin"], 2 * column["hand_joint"] + 0.1)


def test_same_seed_same_samples_other_seed_others() -> None:
    arm = robot(ARM)
    assert np.array_equal(sample_positions(arm, 50, 7)[1], sample_positions(arm, 50, 7)[1])
    assert not np.array_equal(sample_positions(arm, 50, 7)[1], sample_positions(arm, 50, 8)[1])
