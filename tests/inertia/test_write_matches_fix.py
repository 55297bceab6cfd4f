"""`inertia --write` and `lint --fix --unsafe-fixes` go through one edit engine: the patch
applies with `patch -p1` and gives the files `lint --fix` writes, macros included, and a
correct `<origin>` stays byte-identical."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest
from linting.test_fix import make_package

from robotdesc.cli import main

ROBOTS = Path(__file__).resolve().parents[2] / "robots"

MACRO = '''<?xml version="1.0"?>
<robot name="parts" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part" params="name mesh ixx iyy izz">
    <link name="${name}">
      <inertial>
        <origin xyz="0 0 0"/>
        <mass value="1"/>
        <inertia ixx="${ixx}" ixy="0" ixz="0" iyy="${iyy}" iyz="0" izz="${izz}"/>
      </inertial>
      <collision><geometry><mesh filename="${mesh}"/></geometry></collision>
    </link>
  </xacro:macro>
  <link name="base"/>
  <xacro:part name="a" mesh="package://fixpkg/meshes/box.stl"
              ixx="0.0166667" iyy="0.0141667" izz="0.00416667"/>
  <xacro:part name="mm" mesh="package://fixpkg/meshes/box_mm.stl"
              ixx="0.0166667" iyy="0.0141667" izz="0.00416667"/>
  <xacro:part name="rot" mesh="package://fixpkg/meshes/box.stl"
              ixx="0.00416667" iyy="0.0141667" izz="0.0166667"/>
  <link name="g">
    <inertial>
      <mass value="1"/>
      <inertia ixx="16666700" ixy="0" ixz="0" iyy="14166700" iyz="0" izz="4166670"/>
    </inertial>
    <collision><geometry><mesh filename="package://fixpkg/meshes/box.stl"/></geometry></collision>
  </link>
  <joint name="j_a" type="fixed"><parent link="base"/><child link="a"/></joint>
  <joint name="j_mm" type="fixed"><parent link="a"/><child link="mm"/></joint>
  <joint name="j_rot" type="fixed"><parent link="a"/><child link="rot"/></joint>
  <joint name="j_g" type="fixed"><parent link="a"/><child link="g"/></joint>
</robot>
'''


@pytest.fixture(autouse=True)
def _own_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", str(tmp_path / "cache"))


def _write_and_apply(package: Path, top: str, monkeypatch, capsys) -> str:
    """Run `inertia --write` in the package, apply the patch with `patch -p1`; its stderr."""
    monkeypatch.chdir(package)
    assert main(["inertia", top, "--write", str(package.parent / "inertia.patch")]) == 0
    err = capsys.readouterr().err
    subprocess.run(["patch", "-p1", "-s", "-i", str(package.parent / "inertia.patch")],
                   cwd=package, check=True)
    return err


def _files(package: Path) -> dict[str, bytes]:
    return {str(p.relative_to(package)): p.read_bytes() for p in sorted(package.rglob("*"))
            if p.is_file()}


@pytest.mark.skipif(shutil.which("patch") is None, reason="needs patch(1)")
def test_mm_mesh_gmm2_and_rotated_tensor_through_a_macro(tmp_path, monkeypatch, capsys):
    one = make_package(tmp_path / "one", MACRO).parents[1]
    two = make_package(tmp_path / "two", MACRO).parents[1]
    err = _write_and_apply(one, "urdf/robot.urdf.xacro", monkeypatch, capsys)
    # the mm link's tensor is right for its mesh scaled to metres (the scale is M108's fix)
    assert "(2 blocks)" in err
    assert "not patched: link 'mm': the source already has the fixed values" in err
    main(["lint", str(two / "urdf/robot.urdf.xacro"), "--fix", "--unsafe-fixes",
          "--select", "I2"])
    assert _files(one) == _files(two)
    text = (one / "urdf/robot.urdf.xacro").read_text()
    assert text != MACRO
    # at the call sites (the macro body's ${...} are not touched), and the g*mm^2 literal
    assert text.count('<inertia ixx="${ixx}"') == 1 and 'ixx="16666700"' not in text
    assert 'name="rot" mesh="package://fixpkg/meshes/box.stl"\n              ixx="0.0166667"' \
        in text
    assert '<origin xyz="0 0 0"/>' in text  # unchanged values keep their text


HEAD_TENSOR = ('      <inertia ixx="${mass*0.00278424345}" ixy="${mass*9.85713879e-06}" '
               'ixz="${mass*0.000144244124}"\n               iyy="${mass*0.0022761124}" '
               'iyz="${mass*-3.0517283e-06}" izz="${mass*0.00352563615}"/>')
HEAD_ORIGIN = '<origin xyz="0.0842292088 8.64389281e-05 0.00457857104" rpy="0 0 0"/>'


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("patch") is None, reason="needs patch(1)")
def test_engineer_placeholder_in_a_macro(tmp_path, monkeypatch, capsys):
    copies = []
    for name in ("one", "two"):
        package = tmp_path / name / "engineer_description"
        shutil.copytree(ROBOTS / "engineer_description", package)
        inertials = package / "urdf" / "inertials.generated.xacro"
        text = inertials.read_text()
        assert HEAD_TENSOR in text and HEAD_ORIGIN in text
        inertials.write_text(text.replace(
            HEAD_TENSOR, '      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.3"/>'))
        copies.append(package)
    one, two = copies
    before = (one / "urdf" / "inertials.generated.xacro").read_bytes()
    err = _write_and_apply(one, "urdf/engineer.urdf.xacro", monkeypatch, capsys)
    assert "(1 blocks)" in err
    main(["lint", str(two), "--fix", "--unsafe-fixes"])
    assert _files(one) == _files(two)
    after = (one / "urdf" / "inertials.generated.xacro").read_bytes()
    changed = [(a, b) for a, b in zip(before.splitlines(), after.splitlines()) if a != b]
    assert len(changed) == 1 and b'<inertia ixx="0.0034803"' in changed[0][1]
    assert HEAD_ORIGIN.encode() in after
