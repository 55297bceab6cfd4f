"""The one forward kinematics (`model.tree.joint_chain` / `link_frames`, which `poses_at` and
the SRDF matrix use) against a direct composition of each joint's origin and motion."""

import numpy as np
from kinematics.robots import ARM, robot

from robotdesc.model.tree import joint_chain, joint_motion, link_frames, parent_joint_of, poses_at
from robotdesc.spatial import pose_matrix
from robotdesc.srdf.sampling import sample_positions


def _direct(arm, values: dict[str, float]) -> dict[str, np.ndarray]:
    parents = parent_joint_of(arm)

    def pose(link: str) -> np.ndarray:
        joint = parents.get(link)
        if joint is None:
            return np.identity(4)
        motion = joint_motion(joint, values.get(joint.name, 0.0))
        return pose(joint.parent) @ pose_matrix(joint.origin) @ motion

    return {link.name: pose(link.name) for link in arm.links}


def test_batched_frames_match_a_direct_composition() -> None:
    arm = robot(ARM)
    names, positions = sample_positions(arm, 20, seed=4)
    tree = joint_chain(arm, names)
    rotations, translations = link_frames(tree, positions)
    for row in range(len(positions)):
        values = dict(zip(names, positions[row].tolist()))
        direct, single = _direct(arm, values), poses_at(arm, values)
        for k, link in enumerate(tree.links):
            assert np.allclose(rotations[row, k], direct[link][:3, :3], atol=1e-12)
            assert np.allclose(translations[row, k], direct[link][:3, 3], atol=1e-12)
            assert np.allclose(single[link], direct[link], atol=1e-12)
