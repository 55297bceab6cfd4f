from kinematics.robots import ARM, robot
from robotdesc.kinematics import tree


def test_adjacency_passes_through_links_without_geometry() -> None:
    arm = robot(ARM)
    solid = [link.name for link in arm.links if tree.has_collision(link)]
    assert tree.adjacent_pairs(arm, solid) == {("base", "upper"), ("fore", "upper"),
                                                ("fore", "hand")}


def test_fixed_joints_merge_links_into_bodies() -> None:
    arm = robot(ARM)
    assert tree.body_of(arm)["wrist"] == "fore"
    assert tree.body_masses(arm)["fore"] == 1.0
    assert tree.fixed_group(arm, "fore") == ["fore", "wrist"]


def test_tree_problem_names_the_first_defect() -> None:
    assert tree.tree_problem(robot(ARM)) is None
    loop = robot('<robot name="r"><link name="a"/><link name="b"/>'
                 '<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>'
                 '<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint></robot>')
    message, element, _ = tree.tree_problem(loop)
    assert "cycle" in message and element == "robot:r"
    two = robot('<robot name="r"><link name="a"/><link name="a"/></robot>')
    assert tree.tree_problem(two)[1] == "link:a"
