"""The simulator finds meshes by the rules of lint (one `MeshLocator`): a relative filename is
taken from the xacro file that wrote the `<mesh>` (not the top file), and absolute paths are
refused unless the config's `[meshes] allow_absolute_paths` allows them."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from mesh.builders import box_triangles, write_binary_stl

import robotdesc
from robotdesc.cli import main
from robotdesc.mesh.context import MeshContext
from robotdesc.mesh.locate import MeshLocator
from robotdesc.mesh.resolve import MeshResolution, ResolveProblemKind
from robotdesc.mesh.settings import MeshSettings
from robotdesc.model.elements import MeshRef, Robot
from robotdesc.sim import run
from robotdesc.sim.load import load_sim_input
from robotdesc.sim.meshes import MeshAssets, SimMeshError

TOP = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts/block.xacro"/>
  <xacro:block name="base"/>
</robot>
"""

PART = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="block" params="name">
    <link name="${name}">
      <inertial><mass value="1"/>
        <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
      <visual><geometry><mesh filename="FILENAME" scale="0.1 0.1 0.1"/></geometry></visual>
      <collision><geometry><mesh filename="FILENAME" scale="0.1 0.1 0.1"/></geometry>
      </collision>
    </link>
  </xacro:macro>
</robot>
"""


def _package(root: Path, filename: str) -> Path:
    """demo/: urdf/robot.urdf.xacro includes urdf/parts/block.xacro, whose `<mesh>` says
    `filename`; the mesh is demo/urdf/parts/meshes/block.stl (none at urdf/meshes/)."""
    package = root / "demo"
    (package / "urdf" / "parts" / "meshes").mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>demo</name></package>")
    (package / "urdf" / "robot.urdf.xacro").write_text(TOP)
    (package / "urdf" / "parts" / "block.xacro").write_text(PART.replace("FILENAME", filename))
    write_binary_stl(package / "urdf" / "parts" / "meshes" / "block.stl", box_triangles())
    return package / "urdf" / "robot.urdf.xacro"


def _mesh(robot: Robot) -> MeshRef:
    geometry = robot.links[0].visuals[0].geometry
    assert isinstance(geometry, MeshRef)
    return geometry


def _lint_lookup(robot: Robot, top: Path, allow_absolute: bool = False) -> MeshResolution:
    """What the lint rules see of the robot's mesh (the driver's mesh context)."""
    settings = MeshSettings(cache=False, allow_absolute_paths=allow_absolute)
    return MeshContext.for_file(robot, str(top), settings).lookup(_mesh(robot)).resolution


def test_relative_mesh_of_an_included_file_resolves_the_same_for_sim_and_lint(
        tmp_path: Path) -> None:
    top = _package(tmp_path, "meshes/block.stl")
    expected = os.path.realpath(top.parent / "parts" / "meshes" / "block.stl")
    loaded = load_sim_input(str(top))
    asset = loaded.meshes.asset(_mesh(loaded.robot))
    assert asset.source == expected
    assert _lint_lookup(loaded.robot, top).path == expected
    result = robotdesc.lint(str(top), select=["M", "P"])
    assert not [d for d in result.diagnostics if d.code in ("M101", "M103", "M104", "P101")]


def test_an_absolute_mesh_path_is_refused_by_default_in_sim_and_lint(tmp_path: Path) -> None:
    mesh = tmp_path / "demo" / "urdf" / "parts" / "meshes" / "block.stl"
    top = _package(tmp_path, str(mesh))
    loaded = load_sim_input(str(top))
    ref = _mesh(loaded.robot)
    with pytest.raises(SimMeshError, match="absolute path") as caught:
        loaded.meshes.asset(ref)
    assert caught.value.span is not None
    assert caught.value.span.path.endswith("block.xacro")  # the `<mesh>` line, in its file
    refused = _lint_lookup(loaded.robot, top)
    assert refused.problem is not None
    assert refused.problem.kind is ResolveProblemKind.ABSOLUTE_NOT_ALLOWED
    assert "P101" in {d.code for d in robotdesc.lint(str(top), select=["P101"]).diagnostics}
    # both accept it where the config allows absolute paths
    allowing = load_sim_input(str(top), allow_absolute=True)
    assert allowing.meshes.asset(_mesh(allowing.robot)).source == os.path.realpath(mesh)
    assert _lint_lookup(loaded.robot, top, allow_absolute=True).path == os.path.realpath(mesh)


def test_the_sim_command_takes_the_policy_from_the_config(tmp_path: Path) -> None:
    pytest.importorskip("mujoco")
    mesh = tmp_path / "demo" / "urdf" / "parts" / "meshes" / "block.stl"
    top = _package(tmp_path, str(mesh))
    arguments = ["sim", str(top), "--seconds", "0.05", "--no-rtf"]
    assert main(arguments) == 2  # refused: exit 2, naming the `<mesh>`
    (tmp_path / "demo" / "robotdesc.toml").write_text("[meshes]\nallow_absolute_paths = true\n")
    assert main(arguments) in (0, 1)  # simulated (pass or fail is not the point here)


@pytest.mark.parametrize("allowed", [False, True])
def test_the_generated_variant_keeps_the_mesh_policy(monkeypatch: pytest.MonkeyPatch,
                                                     allowed: bool) -> None:
    """`sim --collision generated` makes its collision meshes under the same `[meshes]` policy
    as the rest of the run."""
    seen: dict[str, object] = {}

    def fake_parts(robot: Robot, **kwargs: object) -> dict[str, tuple[object, ...]]:
        seen.update(kwargs)
        return {}

    monkeypatch.setattr(run, "generated_parts", fake_parts)
    monkeypatch.setattr(run, "build_scene", lambda *args, **kwargs: "scene")
    robot = Robot(name="r")
    meshes = MeshAssets(MeshLocator(robot, lambda name: None, allowed))
    assert run.scene_for(robot, meshes, run.SimOptions(), "generated") == "scene"
    assert seen["allow_absolute_paths"] is allowed
