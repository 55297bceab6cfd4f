"""The display scene: placement, shared shapes, problems, face counts; on real robots too."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from support import example_robot_data_dir

import robotdesc
from robotdesc.errors import UsageError
from robotdesc.view.scene import build_scene

from .robots import write_demo_package


@pytest.fixture
def demo(tmp_path: Path):
    return robotdesc.load(str(write_demo_package(tmp_path)))


def test_every_geometry_is_placed_at_the_configuration(demo) -> None:
    scene = build_scene(demo, {"shoulder": np.pi / 2, "grip": 0.03})
    by_key = {(i.link, i.kind, i.index): i for i in scene.instances}
    assert set(by_key) == {("base", "visual", 0), ("base", "collision", 0), ("arm", "visual", 0),
                           ("arm", "collision", 0), ("finger_left", "visual", 0),
                           ("finger_right", "visual", 0)}
    # the arm turned 90 degrees about y: its visual origin (0 0 0.1) now points along +x
    assert np.allclose(by_key[("arm", "visual", 0)].transform[:3, 3], [0.1, 0, 0.05])
    left = scene.link_poses["finger_left"][:3, 3]
    right = scene.link_poses["finger_right"][:3, 3]
    assert np.allclose(left, [0.2, 0.05, 0.05]) and np.allclose(right, [0.2, -0.05, 0.05])
    assert scene.configuration == pytest.approx(
        {"shoulder": np.pi / 2, "grip": 0.03, "grip_mirror": -0.03})


def test_a_mesh_file_at_one_scale_is_stored_once_and_scaled(demo) -> None:
    scene = build_scene(demo)
    labels = [g.label for g in scene.geometries]
    assert labels.count("block.stl") == 2  # two scales, three uses
    arm = next(i for i in scene.instances if i.link == "arm" and i.kind == "visual")
    extent = np.ptp(scene.geometries[arm.geometry].vertices, axis=0)
    assert np.allclose(extent, [0.05, 0.05, 0.2], atol=1e-6)
    fingers = [i.geometry for i in scene.instances if i.link.startswith("finger")]
    assert fingers[0] == fingers[1]


def test_material_colours_and_problems(demo) -> None:
    scene = build_scene(demo)
    base = next(i for i in scene.instances if i.link == "base" and i.kind == "visual")
    assert base.color == pytest.approx((0.1, 0.2, 0.9, 1.0))
    assert [(p.link, p.kind) for p in scene.problems] == [("finger_right", "collision")]
    assert "missing.stl" in scene.problems[0].message


def test_inertia_boxes_and_face_counts(demo) -> None:
    scene = build_scene(demo)
    boxes = {b.link: b for b in scene.inertia_boxes}
    assert set(boxes) == {"base", "arm", "finger_left", "finger_right"}
    assert sorted(boxes["base"].size) == pytest.approx([0.1, 0.2, 0.4], rel=1e-3)
    assert np.allclose(boxes["arm"].transform[:3, 3], [0, 0, 0.15])  # link at z 0.05 + COM
    assert scene.faces_per_link("visual") == {"base": 12, "arm": 12, "finger_left": 12,
                                              "finger_right": 12}
    assert scene.faces_per_link("collision") == {"base": 12, "arm": 96}
    low, high = scene.bounds()
    assert np.allclose(low[:2], [-0.2, -0.1]) and high[2] == pytest.approx(0.275, abs=1e-6)


def test_kinds_and_budget(demo) -> None:
    scene = build_scene(demo, kinds=("collision",), max_faces=20)
    assert {i.kind for i in scene.instances} == {"collision"}
    cylinder = next(g for g in scene.geometries if g.label.startswith("cylinder"))
    assert cylinder.source_faces == 96 and len(cylinder.faces) == 96  # primitives are not reduced


def test_bad_configuration_is_a_usage_error(demo) -> None:
    with pytest.raises(UsageError, match="grip_mirror"):
        build_scene(demo, {"grip_mirror": 0.01})


@pytest.mark.parametrize("name", [
    "ur_description/urdf/ur5_robot.urdf",
    pytest.param("talos_data/robots/talos_reduced.urdf", marks=pytest.mark.slow),
])
def test_example_robot_data(name: str) -> None:
    root = example_robot_data_dir()
    urdf = root / name if root else None
    if urdf is None or not urdf.is_file():
        pytest.skip(f"{name} is not in this example-robot-data")
    robot = robotdesc.load(str(urdf))
    scene = build_scene(robot, max_faces=2_000,
                        package_map=(("example-robot-data", str(root.parent)),))
    assert not scene.problems
    assert len(scene.instances) >= len([v for link in robot.links for v in link.visuals])
    assert all(len(g.faces) <= 2_000 or g.primitive for g in scene.geometries)
    low, high = scene.bounds()
    assert 0.3 < float(np.max(high - low)) < 3.0  # metres: a robot arm or a humanoid
