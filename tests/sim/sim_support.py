"""Helpers of the physics tests: fixture paths, example-robot-data, loading, and the
suggested-inertia variant of a robot (through robotdesc's inertia API)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest
from support import example_robot_data_dir

FIXTURES = Path(__file__).parent / "fixtures"
_ROBOTS = example_robot_data_dir()
ERD = _ROBOTS.parent if _ROBOTS is not None else Path("example-robot-data-not-installed")


@pytest.fixture(scope="session")
def erd_options():
    """ExpandOptions that resolve `package://example-robot-data/...` (skips without it)."""
    if not (ERD / "robots").is_dir():
        pytest.skip("example-robot-data is not installed")
    from robotdesc.expansion import ExpandOptions

    return ExpandOptions(package_map=(("example-robot-data", str(ERD)),))


def load(path, expand_options=None):
    """(robot, mesh assets) of a description."""
    from robotdesc.sim.load import load_sim_input

    loaded = load_sim_input(str(path), expand_options=expand_options)
    return loaded.robot, loaded.meshes


def with_suggested_inertias(robot):
    """`robot` with every link's inertial replaced by robotdesc's suggestion (inertia API)."""
    from robotdesc.inertia.suggest import suggest_inertial
    from robotdesc.mesh.context import MeshContext
    from robotdesc.mesh.settings import MeshSettings
    from robotdesc.model.elements import Inertia, Inertial, Pose

    context = MeshContext(robot, MeshSettings(cache=False), lambda name: None)
    links = []
    for link in robot.links:
        geometry = context.link_geometry(link)
        if geometry.properties is None or link.inertial is None:
            links.append(link)
            continue
        body = suggest_inertial(link, geometry.properties).properties
        (ixx, ixy, ixz), (_, iyy, iyz), (_, _, izz) = body.inertia
        inertial = Inertial(Pose(tuple(body.center_of_mass)), body.mass,
                            Inertia(ixx, ixy, ixz, iyy, iyz, izz), link.inertial.where)
        links.append(dataclasses.replace(link, inertial=inertial))
    return dataclasses.replace(robot, links=tuple(links))
