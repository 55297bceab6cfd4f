import numpy as np
from kinematics.robots import ARM, robot

from robotdesc.model.tree import poses_at
from robotdesc.srdf.forward import chain, link_frames
from robotdesc.srdf.sampling import sample_positions


def test_batched_frames_match_the_forward_kinematics_of_one_configuration() -> None:
    arm = robot(ARM)
    names, positions = sample_positions(arm, 20, seed=4)
    tree = chain(arm, names)
    rotations, translations = link_frames(tree, positions)
    for row in range(len(positions)):
        poses = poses_at(arm, dict(zip(names, positions[row].tolist())))
        for k, link in enumerate(tree.links):
            assert np.allclose(rotations[row, k], poses[link][:3, :3], atol=1e-12)
            assert np.allclose(translations[row, k], poses[link][:3, 3], atol=1e-12)
