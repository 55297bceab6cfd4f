"""`robotdesc lint --fix` / `--diff` / `--unsafe-fixes`: each fix kind, in macro bodies, at
call sites, refused on expressions, byte-faithful, idempotent and safe to write."""

from __future__ import annotations

from pathlib import Path

import pytest
from mesh.builders import box_triangles, write_binary_stl

from robotdesc.cli import main
from robotdesc.linting.driver import lint_file
from robotdesc.linting.fix import plan_fixes, write_fixes

PACKAGE_XML = ('<?xml version="1.0"?>\n<package format="3"><name>fixpkg</name>'
               '<version>0.0.0</version><description>x</description>'
               '<maintainer email="a@b.c">a</maintainer><license>MIT</license></package>\n')

ROBOT = '''<?xml version="1.0"?>
<!-- a package with fixable mistakes -->
<robot name="fixme" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part" params="name mesh ixx iyy izz scale">
    <link name="${name}">
      <inertial>
        <origin xyz="0 0 0"/>   <!-- keep me -->
        <mass value="1"/>
        <inertia ixx="${ixx}" ixy="0" ixz="0" iyy="${iyy}" iyz="0" izz="${izz}"/>
      </inertial>
      <collision><geometry><mesh filename="${mesh}" scale="${scale}"/></geometry></collision>
    </link>
  </xacro:macro>
  <link name="base"/>
  <xacro:part name="a" mesh="package://fixpkg/meshes/box.stl" scale="1 1 1"
              ixx="0.0166667" iyy="0.0141667" izz="0.00416667"/>
  <xacro:part name="mm" mesh="package://fixpkg/meshes/box_mm.stl" scale="1 1 1"
              ixx="0.0166667" iyy="0.0141667" izz="0.00416667"/>  <!-- millimetres -->
  <xacro:part name="rot" mesh="package://fixpkg/meshes/box.stl" scale="1 1 1"
              ixx="0.00416667" iyy="0.0141667" izz="0.0166667"/>
  <link name="b">
    <inertial>
      <origin xyz="0 0 0"/>
      <mass value="1"/>
      <inertia ixx="16666700" ixy="0" ixz="0" iyy="14166700" iyz="0" izz="4166670"/>
    </inertial>
    <collision><geometry><mesh filename="file://PKG/meshes/box.stl"/></geometry></collision>
    <visual><geometry><mesh filename="package://fixpkg/meshes/cronstain.stl"/></geometry></visual>
  </link>
  <joint name="j_a" type="revolute">
    <parent link="base"/><child link="a"/>
    <axis xyz="0 0 2"/>
    <limit lower="1.5"  upper="-1.5" effort="10" velocity="1"/>
  </joint>
  <joint name="j_mm" type="fixed"><parent link="a"/><child link="mm"/></joint>
  <joint name="j_b" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="j_rot" type="fixed"><parent link="a"/><child link="rot"/></joint>
</robot>
'''

FIXED_CODES = ("I201", "I204", "J103", "J107", "M102", "M108", "P102")


def make_package(root: Path, robot: str = ROBOT) -> Path:
    """A package with the meshes the robot names; returns the robot file."""
    package = root / "fixpkg"
    (package / "urdf").mkdir(parents=True)
    (package / "meshes").mkdir()
    (package / "package.xml").write_text(PACKAGE_XML)
    box = box_triangles((0.1, 0.2, 0.4))
    write_binary_stl(package / "meshes" / "box.stl", box)
    write_binary_stl(package / "meshes" / "box_mm.stl", box * 1000)
    write_binary_stl(package / "meshes" / "Cronstain.stl", box)
    path = package / "urdf" / "robot.urdf.xacro"
    path.write_text(robot.replace("PKG", str(package)))
    return path


@pytest.fixture(autouse=True)
def _own_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", str(tmp_path / "cache"))


def _codes(path: Path) -> set[str]:
    return {d.code for d in lint_file(str(path)).diagnostics}


def test_fix_unsafe_leaves_the_package_clean_with_a_minimal_diff(tmp_path, capsys):
    path = make_package(tmp_path)
    before = path.read_text()
    assert set(FIXED_CODES) - {"I201"} <= _codes(path)
    main(["lint", str(path), "--fix", "--unsafe-fixes"])
    after = path.read_text()
    assert not _codes(path) & set(FIXED_CODES)
    changed = [(a, b) for a, b in zip(before.splitlines(), after.splitlines()) if a != b]
    assert len(before.splitlines()) == len(after.splitlines())
    assert len(changed) == 7  # scale arg, rotated args, g*mm^2 tensor, 2 filenames, axis, limit
    assert '<origin xyz="0 0 0"/>   <!-- keep me -->' in after
    assert 'scale="1 1 1"\n              ixx="0.0166667" iyy="0.0141667" izz="0.00416667"/>  ' \
           "<!-- millimetres -->" not in after
    assert 'mesh="package://fixpkg/meshes/box_mm.stl" scale="0.001 0.001 0.001"' in after
    assert '<limit lower="-1.5"  upper="1.5" effort="10"' in after  # spacing kept
    assert 'filename="package://fixpkg/meshes/box.stl"/></geometry></collision>\n' \
           '    <visual><geometry><mesh filename="package://fixpkg/meshes/Cronstain.stl"' in after
    # idempotent: nothing left to fix, nothing written
    capsys.readouterr()
    assert main(["lint", str(path), "--diff", "--unsafe-fixes"]) == 0
    assert capsys.readouterr().out == ""


def test_fix_applies_safe_fixes_only_without_unsafe_flag(tmp_path, capsys):
    path = make_package(tmp_path)
    main(["lint", str(path), "--fix"])
    text = path.read_text()
    assert '<axis xyz="0 0 1"/>' in text and "Cronstain.stl" in text
    assert '<limit lower="1.5"  upper="-1.5"' in text  # J103 is unsafe
    assert "more fixable with --unsafe-fixes" in capsys.readouterr().err
    assert {"J103", "M108"} <= _codes(path)


def test_diff_writes_nothing(tmp_path, capsys):
    path = make_package(tmp_path)
    before = path.read_bytes()
    assert main(["lint", str(path), "--diff"]) == 1
    out = capsys.readouterr().out
    assert out.startswith("--- a/") and '+    <axis xyz="0 0 1"/>' in out
    assert path.read_bytes() == before


MACRO_BODY = '''<?xml version="1.0"?>
<robot name="m" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="wheel" params="n">
    <link name="w${n}"/>
    <joint name="j${n}" type="continuous">
      <parent link="base"/><child link="w${n}"/>
      <axis xyz="0 2 0"/> <!-- body literal -->
    </joint>
  </xacro:macro>
  <xacro:macro name="arm" params="lo">
    <link name="arm"/>
    <joint name="arm_j" type="revolute">
      <parent link="base"/><child link="arm"/><axis xyz="1 0 0"/>
      <limit lower="${lo}" upper="${-lo * 2}" effort="1" velocity="1"/>
    </joint>
  </xacro:macro>
  <link name="base"/>
  <xacro:wheel n="1"/>
  <xacro:wheel n="2"/>
  <xacro:arm lo="1"/>
</robot>
'''


def test_macro_body_literal_is_fixed_once_for_every_call(tmp_path):
    path = make_package(tmp_path, MACRO_BODY)
    main(["lint", str(path), "--fix", "--select", "J107"])
    text = path.read_text()
    assert '<axis xyz="0 1 0"/> <!-- body literal -->' in text
    assert "J107" not in _codes(path)


def test_fix_refused_on_an_expression(tmp_path, capsys):
    path = make_package(tmp_path, MACRO_BODY)
    before = path.read_bytes()
    main(["lint", str(path), "--fix", "--unsafe-fixes", "--select", "J103"])
    err = capsys.readouterr().err
    assert ("J103 fix not applicable: computed at urdf/robot.urdf.xacro:14: the expression "
            "'${-lo * 2}'") in err
    assert path.read_bytes() == before


def test_shared_macro_literal_is_not_fixed_for_one_call(tmp_path, capsys):
    robot = MACRO_BODY.replace('<xacro:wheel n="2"/>', '').replace(
        '<axis xyz="0 2 0"/>', '<axis xyz="${axis}"/>').replace(
        'params="n"', 'params="n axis"').replace('<xacro:wheel n="1"/>',
                                                  '<xacro:wheel n="1" axis="0 3 0"/>')
    path = make_package(tmp_path, robot)
    main(["lint", str(path), "--fix", "--select", "J107"])
    assert '<xacro:wheel n="1" axis="0 1 0"/>' in path.read_text()  # at the call site


def test_write_refused_when_the_file_changed_since_read(tmp_path):
    path = make_package(tmp_path)
    plan = plan_fixes([lint_file(str(path))])
    assert plan.files
    path.write_text(path.read_text() + "<!-- edited meanwhile -->\n")
    written, refused = write_fixes(plan)
    assert written == [] and refused == [str(path)]
    assert path.read_text().endswith("<!-- edited meanwhile -->\n")


def test_fix_outside_the_package_is_not_applicable(tmp_path):
    other = tmp_path / "other"
    other.mkdir()
    (other / "axis.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:macro name="j"><joint name="j" type="continuous"><parent link="base"/>'
        '<child link="c"/><axis xyz="0 0 3"/></joint></xacro:macro>\n</robot>\n')
    robot = ('<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
             f'\n  <xacro:include filename="{other}/axis.xacro"/>\n  <link name="base"/>'
             '<link name="c"/>\n  <xacro:j/>\n</robot>\n')
    path = make_package(tmp_path, robot)
    from robotdesc.expansion import ExpandOptions

    result = lint_file(str(path), expand_options=ExpandOptions(trusted=True), select=["J107"])
    plan = plan_fixes([result])
    assert not plan.files
    assert "outside the linted package" in plan.outcomes[0].reason
