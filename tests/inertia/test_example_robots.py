"""Inertia and mesh rules over example-robot-data: no crash, real findings pinned, and robots
that must stay free of inertia errors."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import pytest
from support import example_robot_data_dir, example_robot_urdfs

from robotdesc.diagnostics import Severity
from robotdesc.expansion import ExpandOptions
from robotdesc.linting.driver import lint_file

ROBOTS = example_robot_data_dir()
pytestmark = pytest.mark.skipif(ROBOTS is None, reason="example-robot-data is not installed")
FAMILIES = ["I", "M", "B"]


def lint(name: str):
    [path] = [p for p in example_robot_urdfs() if p.name == name]
    options = ExpandOptions(package_map=(("example-robot-data", str(ROBOTS.parent)),))
    return lint_file(str(path), select=FAMILIES, expand_options=options).diagnostics


def codes(name: str) -> Counter:
    return Counter(d.code for d in lint(name))


def test_known_zero_masses_and_zero_inertias() -> None:
    assert codes("romeo.urdf")["I102"] == 24  # moving links of mass 0
    icub = [d for d in lint("icub.urdf") if d.code == "I103"]
    assert len(icub) == 12 and any("'head'" in d.message and "is zero" in d.message
                                   for d in icub)
    # the F/T sensor links are point masses on fixed joints, lumped into their parents:
    # I103 allows them, and I201 leaves singular tensors to I103 (issue 14, precision)
    talos = [d for d in lint("talos_reduced.urdf") if d.code in ("I201", "I103")]
    assert not any("_ft_" in d.message for d in talos)


def test_known_triangle_violations_and_placeholders() -> None:
    allegro = [d for d in lint("allegro_right_hand.urdf") if d.code == "I104"]
    assert len(allegro) == 4 and "20.4% of the largest" in allegro[0].message
    assert codes("baxter.urdf")["I105"] == 2
    assert codes("tiago.urdf")["I103"] == 2  # the antennas' negative moments


def test_known_mesh_problems() -> None:
    panda = {d.element: d for d in lint("panda.urdf")}
    assert "link:panda_link1/inertial" in panda  # Franka's published link1 tensor
    assert panda["link:panda_link1/inertial"].fix.startswith("<inertial>")
    assert codes("romeo_laas_small.urdf")["M101"] == 0  # file:// meshes are P102's


def test_go1_base_tensor_is_singular_and_its_trunk_mesh_is_read() -> None:
    """go1's `base` (a root link of 1e-6 kg) has a rank-1 tensor MuJoCo refuses (I103);
    its 28 MB trunk.dae has a float array over libxml2's text limit and is read (no M107)."""
    found = codes("go1.urdf")
    assert found["I103"] == 1 and found["M107"] == 0


def test_anymal_foot_is_read_and_its_broken_material_is_m116() -> None:
    found = codes("anymal-kinova.urdf")  # ANYmal B's four feet use anymal_foot.dae
    assert found["M107"] == 0 and found["M116"] == 1


@pytest.mark.parametrize("name", ["ur5_robot.urdf", "solo12.urdf", "z1.urdf",
                                  "kinova.urdf", "talos_reduced.urdf"])
def test_robots_free_of_inertia_errors(name: str) -> None:
    errors = [d for d in lint(name) if d.code.startswith("I") and d.severity >= Severity.ERROR]
    assert errors == []


@pytest.mark.slow
@pytest.mark.parametrize("path", example_robot_urdfs(), ids=lambda p: p.name)
def test_every_example_robot_lints_with_mesh_rules(path: Path) -> None:
    options = ExpandOptions(package_map=(("example-robot-data", str(ROBOTS.parent)),))
    for diagnostic in lint_file(str(path), select=FAMILIES, expand_options=options).diagnostics:
        assert diagnostic.where is not None and diagnostic.message
