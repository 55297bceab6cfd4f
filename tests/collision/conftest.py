"""Real meshes from example-robot-data, and a tiny ROS package built around them."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest
from support import example_robot_data_dir

ROBOTS = example_robot_data_dir()


def real_mesh(relative: str) -> Path:
    if ROBOTS is None:
        pytest.skip("example-robot-data is not installed")
    return ROBOTS / relative


HIP = "solo_description/meshes/stl/solo12/solo12_hip_fe_fl.stl"      # closed, 3078 faces
LINK1 = "panda_description/meshes/visual/link1.dae"                  # closed, 12516 faces
FOREARM = "ur_description/meshes/ur5/visual/forearm.dae"               # closed, 21028 faces
UPPERARM = "ur_description/meshes/ur5/visual/upperarm.dae"             # closed, 29436 faces
Z1_LINK03 = "z1_description/meshes/collision/z1_Link03.STL"            # closed, 33580 faces
SO101_HOLDER = "so_arm_description/meshes/so101/base_motor_holder_so101_v1.stl"  # closed, 37540
Z1_LINK05 = "z1_description/meshes/collision/z1_Link05.STL"  # closed; fast-simplification: 21 %
UPPER_LEG = "solo_description/meshes/stl/solo12/solo12_upper_leg_left_side.stl"  # open


@pytest.fixture
def package(tmp_path: Path) -> Path:
    """A package `demo` with a URDF of two good links (real meshes) and a primitive link."""
    root = tmp_path / "demo"
    (root / "meshes").mkdir(parents=True)
    (root / "urdf").mkdir()
    (root / "package.xml").write_text("<package format='3'><name>demo</name></package>")
    shutil.copy(real_mesh(HIP), root / "meshes" / "hip.stl")
    shutil.copy(real_mesh(UPPER_LEG), root / "meshes" / "leg.stl")
    return root


def write_urdf(root: Path, links: dict[str, str], name: str = "demo.urdf") -> Path:
    """A URDF whose link NAME has a visual mesh `package://demo/meshes/FILE`."""
    body = []
    for link, mesh in links.items():
        body.append(f'<link name="{link}"><visual><geometry><mesh filename='
                    f'"package://demo/meshes/{mesh}"/></geometry></visual>'
                    f'<collision><geometry><box size="1 1 1"/></geometry></collision></link>')
    joints = [f'<joint name="j{i}" type="fixed"><parent link="{a}"/><child link="{b}"/></joint>'
              for i, (a, b) in enumerate(zip(list(links), list(links)[1:]))]
    path = root / "urdf" / name
    path.write_text('<?xml version="1.0"?>\n<robot name="demo">\n' + "\n".join(body + joints)
                    + "\n</robot>\n")
    return path


def box_soup(size=(0.1, 0.2, 0.3)) -> np.ndarray:
    from mesh.builders import box_triangles

    return box_triangles(size)
