"""The model's kinematic tree: parents, children, roots, cycles, fixed-joint groups, mimics."""

from __future__ import annotations

import subprocess
import sys

from kinematics.robots import ARM, robot

from robotdesc.model import tree

LOOP = ('<robot name="r"><link name="a"/><link name="b"/><link name="c"/><link name="d"/>'
        '<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>'
        '<joint name="bc" type="fixed"><parent link="b"/><child link="c"/></joint>'
        '<joint name="cb" type="fixed"><parent link="c"/><child link="b"/></joint>'
        '<joint name="dd" type="fixed"><parent link="d"/><child link="d"/></joint></robot>')


def test_adjacency_passes_through_links_without_geometry() -> None:
    arm = robot(ARM)
    solid = [link.name for link in arm.links if tree.has_collision(link)]
    assert tree.adjacent_pairs(arm, solid) == {("base", "upper"), ("fore", "upper"),
                                                ("fore", "hand")}


def test_fixed_joints_merge_links_into_bodies() -> None:
    arm = robot(ARM)
    assert tree.body_of(arm)["wrist"] == "fore"
    assert tree.body_of(arm, keep={"wrist_joint"})["wrist"] == "wrist"
    assert tree.body_masses(arm)["fore"] == 1.0
    assert tree.fixed_group(arm, "fore") == ["fore", "wrist"]


def test_parents_children_roots_and_subtrees() -> None:
    arm = robot(ARM)
    assert [j.name for j in tree.children_of(arm)["base"]] == ["shoulder", "hand_twin"]
    assert tree.parent_joint_of(arm)["hand"].name == "hand_joint"
    assert [link.name for link in tree.roots(arm)] == ["base"]
    assert tree.subtree(arm, "upper") == ["upper", "fore", "wrist", "hand"]
    lone = robot('<robot name="r"><link name="a"/><link name="b"/><link name="c"/>'
                 '<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>'
                 '</robot>')
    assert [link.name for link in tree.roots(lone)] == ["a", "c"]
    assert [link.name for link in tree.connected_roots(lone)] == ["a"]
    assert tree.mentioned_links(lone) == {"a", "b"}


def test_cycles_name_their_first_joint_and_links() -> None:
    loop = robot(LOOP)
    assert [(joint.name, members) for joint, members in tree.cycles(loop)] == [
        ("bc", ["b", "c"])]
    assert [joint.name for joint in tree.self_joints(loop)] == ["dd"]
    assert tree.cycles(robot(ARM)) == []


def test_mimic_joints_follow_their_leader() -> None:
    arm = robot(ARM)
    assert [(j.name, name) for j, name in tree.mimicking(arm)] == [("hand_twin", "hand_joint")]
    assert tree.mimic_value(arm.joint("hand_twin"), 0.15) == 2 * 0.15 + 0.1
    assert tree.configuration(arm)["hand_twin"] == 2 * 0.1 + 0.1  # hand_joint at its lower


def test_tree_problem_names_the_first_defect() -> None:
    assert tree.tree_problem(robot(ARM)) is None
    loop = robot('<robot name="r"><link name="a"/><link name="b"/>'
                 '<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>'
                 '<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint></robot>')
    message, element, _ = tree.tree_problem(loop)
    assert "cycle" in message and element == "robot:r"
    two = robot('<robot name="r"><link name="a"/><link name="a"/></robot>')
    assert tree.tree_problem(two)[1] == "link:a"


def test_the_tree_imports_without_numpy() -> None:
    """The model layer stays importable (and a lint stays light) without numpy."""
    code = ("import sys; import robotdesc.model.tree, robotdesc.model.summary; "
            "assert 'numpy' not in sys.modules, 'numpy imported'")
    subprocess.run([sys.executable, "-c", code], check=True)
