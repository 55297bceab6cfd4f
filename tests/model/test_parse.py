"""The strict URDF parser: refusals, provenance, every model field, unreadable values."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from support import example_robot_urdfs

from robotdesc.errors import InputError, XmlSyntaxError
from robotdesc.model.elements import (
    Box,
    Capsule,
    Cylinder,
    Inertia,
    MeshRef,
    Pose,
    Sphere,
)
from robotdesc.model.parse import parse_urdf
from robotdesc.source import PROVENANCE_ATTR, Provenance, Span, decode_provenance, strip_provenance

FULL = b"""<?xml version="1.0"?>
<robot name="arm">
  <material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>
  <material name="skin"><texture filename="skin.png"/></material>
  <link name="base">
    <inertial>
      <origin xyz="0 0 0.05" rpy="0 0 1"/>
      <mass value="2.5"/>
      <inertia ixx="0.1" ixy="0.01" ixz="0.02" iyy="0.2" iyz="0.03" izz="0.3"/>
    </inertial>
    <visual name="shell">
      <origin xyz="1 2 3"/>
      <geometry><mesh filename="package://arm/base.stl" scale="0.001 0.001 0.001"/></geometry>
      <material name="grey"/>
    </visual>
    <visual>
      <geometry><box size="0.1 0.2 0.3"/></geometry>
      <material name="red"><color rgba="1 0 0 1"/></material>
    </visual>
    <collision name="hull">
      <geometry><cylinder radius="0.1" length="0.4"/></geometry>
    </collision>
    <collision><geometry><sphere radius="0.05"/></geometry></collision>
    <collision><geometry><capsule radius="0.02" length="0.3"/></geometry></collision>
    <sensor name="ignored"/>
  </link>
  <link name="upper"/>
  <joint name="shoulder" type="revolute">
    <origin xyz="0 0 0.1" rpy="0 0.5 0"/>
    <parent link="base"/>
    <child link="upper"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="30" velocity="2"/>
    <dynamics damping="0.7" friction="0.1"/>
    <mimic joint="other" multiplier="2" offset="0.5"/>
    <safety_controller soft_lower_limit="-1.4" soft_upper_limit="1.4"
                       k_position="15" k_velocity="10"/>
    <calibration rising="0.1" falling="0.2"/>
    <unknown_extension/>
  </joint>
  <joint name="plain" type="fixed"><parent link="base"/><child link="upper"/></joint>
  <transmission name="ros1">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="shoulder">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      <hardwareInterface>PositionJointInterface</hardwareInterface>
    </joint>
    <actuator name="motor">
      <hardwareInterface>EffortJointInterface</hardwareInterface>
      <mechanicalReduction>50</mechanicalReduction>
    </actuator>
  </transmission>
  <transmission name="pr2" type="pr2_mechanism_model/SimpleTransmission">
    <actuator name="old_motor"/>
    <joint name="plain"/>
    <mechanicalReduction>-79.2</mechanicalReduction>
  </transmission>
  <gazebo reference="base">
    <material>Gazebo/Grey</material>
    <sensor name="cam"><plugin name="c" filename="libcamera.so"/></sensor>
  </gazebo>
  <gazebo>
    <plugin name="control" filename="libgazebo_ros_control.so"/>
  </gazebo>
  <ros2_control name="ignored"/>
</robot>
"""


def line_of(data: bytes, needle: bytes) -> int:
    return data[:data.index(needle)].count(b"\n") + 1


# -- a well-formed robot: every field --------------------------------------------------------

def test_robot_level_fields() -> None:
    robot = parse_urdf(FULL, "arm.urdf")
    assert robot.name == "arm"
    assert robot.source == "arm.urdf"
    assert robot.where == Provenance(Span("arm.urdf", 2, 1))
    assert [link.name for link in robot.links] == ["base", "upper"]
    assert [joint.name for joint in robot.joints] == ["shoulder", "plain"]
    assert robot.value_issues == ()


def test_materials_robot_level_and_inline() -> None:
    robot = parse_urdf(FULL, "arm.urdf")
    grey, skin = robot.materials
    assert (grey.name, grey.color, grey.texture) == ("grey", (0.5, 0.5, 0.5, 1.0), None)
    assert (skin.name, skin.color, skin.texture) == ("skin", None, "skin.png")
    shell, boxed = robot.links[0].visuals
    assert shell.material.name == "grey" and shell.material.color is None
    assert boxed.material.color == (1.0, 0.0, 0.0, 1.0)
    assert boxed.material.where.span.line == line_of(FULL, b'<material name="red">')


def test_link_inertial_and_geometry() -> None:
    base = parse_urdf(FULL, "arm.urdf").link("base")
    inertial = base.inertial
    assert inertial.mass == 2.5
    assert inertial.origin == Pose((0.0, 0.0, 0.05), (0.0, 0.0, 1.0), inertial.origin.where)
    assert inertial.inertia.matrix() == ((0.1, 0.01, 0.02), (0.01, 0.2, 0.03), (0.02, 0.03, 0.3))
    assert isinstance(inertial.inertia, Inertia)
    shell, boxed = base.visuals
    assert shell.name == "shell" and shell.origin.xyz == (1.0, 2.0, 3.0)
    assert shell.geometry == MeshRef("package://arm/base.stl", (0.001, 0.001, 0.001),
                                     shell.geometry.where)
    assert boxed.name is None and boxed.origin == Pose()
    assert isinstance(boxed.geometry, Box) and boxed.geometry.size == (0.1, 0.2, 0.3)
    hull, ball, capsule = base.collisions
    assert hull.name == "hull"
    assert isinstance(hull.geometry, Cylinder)
    assert (hull.geometry.radius, hull.geometry.length) == (0.1, 0.4)
    assert isinstance(ball.geometry, Sphere) and ball.geometry.radius == 0.05
    assert isinstance(capsule.geometry, Capsule) and capsule.geometry.length == 0.3
    assert parse_urdf(FULL, "arm.urdf").link("upper").inertial is None


def test_joint_fields() -> None:
    robot = parse_urdf(FULL, "arm.urdf")
    joint = robot.joint("shoulder")
    assert (joint.type, joint.parent, joint.child) == ("revolute", "base", "upper")
    assert joint.origin.xyz == (0.0, 0.0, 0.1) and joint.origin.rpy == (0.0, 0.5, 0.0)
    assert joint.axis == (0.0, 1.0, 0.0)
    assert joint.axis_where.span.line == line_of(FULL, b'<axis xyz="0 1 0"/>')
    limit = joint.limit
    assert (limit.lower, limit.upper, limit.effort, limit.velocity) == (-1.5, 1.5, 30.0, 2.0)
    assert (joint.dynamics.damping, joint.dynamics.friction) == (0.7, 0.1)
    assert (joint.mimic.joint, joint.mimic.multiplier, joint.mimic.offset) == ("other", 2.0, 0.5)
    safety = joint.safety_controller
    assert (safety.soft_lower_limit, safety.soft_upper_limit, safety.k_position,
            safety.k_velocity) == (-1.4, 1.4, 15.0, 10.0)
    assert (joint.calibration.rising, joint.calibration.falling) == (0.1, 0.2)
    plain = robot.joint("plain")
    assert plain.axis is None and plain.axis_where is None and plain.limit is None
    assert plain.mimic is None and plain.origin == Pose()


def test_axis_without_xyz_is_urdf_default() -> None:
    robot = parse_urdf(b'<robot name="r"><joint name="j" type="continuous">'
                       b'<parent link="a"/><child link="b"/><axis/></joint></robot>', "r.urdf")
    assert robot.joints[0].axis == (1.0, 0.0, 0.0)


def test_transmissions_in_both_forms() -> None:
    ros1, pr2 = parse_urdf(FULL, "arm.urdf").transmissions
    assert ros1.type == "transmission_interface/SimpleTransmission"
    assert [j.name for j in ros1.joints] == ["shoulder"]
    assert ros1.joints[0].hardware_interfaces == ("hardware_interface/EffortJointInterface",
                                                  "PositionJointInterface")
    assert ros1.actuators[0].name == "motor"
    assert ros1.actuators[0].hardware_interfaces == ("EffortJointInterface",)
    assert ros1.actuators[0].mechanical_reduction == 50.0
    assert pr2.type == "pr2_mechanism_model/SimpleTransmission"
    assert [j.name for j in pr2.joints] == ["plain"]
    assert pr2.actuators[0].name == "old_motor"
    assert pr2.actuators[0].mechanical_reduction == -79.2


def test_gazebo_blocks() -> None:
    referenced, global_ = parse_urdf(FULL, "arm.urdf").gazebo
    assert referenced.reference == "base"
    assert referenced.tags == ("material", "sensor")
    assert referenced.plugins == ("libcamera.so",)
    assert global_.reference is None and global_.plugins == ("libgazebo_ros_control.so",)


def test_plain_urdf_provenance_is_the_element_line() -> None:
    robot = parse_urdf(FULL, "/x/arm.urdf")
    joint = robot.joint("shoulder")
    assert joint.where == Provenance(Span("/x/arm.urdf", line_of(FULL, b'<joint name="shoulder"'), 3))
    assert joint.limit.where.span.line == line_of(FULL, b"<limit lower")
    assert joint.mimic.where.span.line == line_of(FULL, b"<mimic")
    transmission_joint = robot.transmissions[0].joints[0]
    assert transmission_joint.where.span.line == line_of(FULL, b'<joint name="shoulder">')
    assert robot.gazebo[1].where.span.line == line_of(FULL, b"<gazebo>")


def test_accepts_text_and_declared_encodings() -> None:
    assert parse_urdf('<robot name="bras\u00e9"/>', "r.urdf").name == "bras\u00e9"
    latin = '<?xml version="1.0" encoding="ISO-8859-1"?><robot name="\u00e9"/>'.encode("latin-1")
    assert parse_urdf(latin, "r.urdf").name == "\u00e9"


# -- provenance through expansion -------------------------------------------------------------

EXPANDED = f"""<robot name="r" {PROVENANCE_ATTR}="0:1">
  <link name="base" {PROVENANCE_ATTR}="0:3">
    <visual><geometry><box size="1 1 1" {PROVENANCE_ATTR}="1:7;0:4"/></geometry></visual>
  </link>
  <link name="wheel" {PROVENANCE_ATTR}="1:5;1:9*3;0:20">
    <inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
  </link>
</robot>
""".encode()
FILES = ("/pkg/robot.urdf.xacro", "/pkg/wheel.xacro")


def test_provenance_is_decoded_against_the_file_table() -> None:
    robot = parse_urdf(EXPANDED, "/pkg/robot.urdf.xacro", FILES)
    assert robot.where == Provenance(Span("/pkg/robot.urdf.xacro", 1))
    base, wheel = robot.links
    assert base.where == Provenance(Span("/pkg/robot.urdf.xacro", 3))
    assert base.visuals[0].geometry.where == Provenance(Span("/pkg/wheel.xacro", 7),
                                                        (Span("/pkg/robot.urdf.xacro", 4),))
    site = Span("/pkg/wheel.xacro", 9)
    assert wheel.where == Provenance(Span("/pkg/wheel.xacro", 5),
                                     (site, site, site, Span("/pkg/robot.urdf.xacro", 20)))


def test_shared_call_chains_decode_like_decode_provenance() -> None:
    values = ["0:3;1:9*2;0:20", "0:4;1:9*2;0:20", "0:3;1:9;0:20", "0:3", "1:3;0:3"]
    links = "".join(f'<link name="l{i}" {PROVENANCE_ATTR}="{v}"/>' for i, v in enumerate(values))
    robot = parse_urdf(f'<robot name="r">{links}</robot>'.encode(), "r.urdf", FILES)
    assert [link.where for link in robot.links] == [decode_provenance(v, FILES) for v in values]


def test_elements_without_the_attribute_inherit_the_nearest_ancestor() -> None:
    robot = parse_urdf(EXPANDED, "/pkg/robot.urdf.xacro", FILES)
    base, wheel = robot.links
    assert base.visuals[0].where == base.where
    assert wheel.inertial.where == wheel.where
    assert wheel.inertial.inertia.where == wheel.where


def test_attribute_is_ignored_without_a_file_table() -> None:
    robot = parse_urdf(EXPANDED, "out.urdf")
    assert robot.links[1].where == Provenance(Span("out.urdf", 5, 3))


def test_malformed_provenance_falls_back_to_the_ancestor() -> None:
    data = (f'<robot name="r" {PROVENANCE_ATTR}="0:1">'
            f'<link name="a" {PROVENANCE_ATTR}="7:x"/></robot>')
    robot = parse_urdf(data.encode(), "r.urdf", ("/a.xacro",))
    assert robot.links[0].where == Provenance(Span("/a.xacro", 1))


def test_strip_provenance_removes_only_the_private_attribute() -> None:
    stripped = strip_provenance(EXPANDED)
    assert PROVENANCE_ATTR.encode() not in stripped
    assert stripped == EXPANDED.replace(f' {PROVENANCE_ATTR}="0:1"'.encode(), b"") \
        .replace(f' {PROVENANCE_ATTR}="0:3"'.encode(), b"") \
        .replace(f' {PROVENANCE_ATTR}="1:7;0:4"'.encode(), b"") \
        .replace(f' {PROVENANCE_ATTR}="1:5;1:9*3;0:20"'.encode(), b"")
    assert parse_urdf(stripped, "s.urdf").links[1].inertial.mass == 1.0
    untouched = b'<robot name="r"><!-- _rd_src="1:2" in a comment --><link name="a"/></robot>'
    assert strip_provenance(untouched) == untouched
    mixed = (b'<?xml version="1.0"?>\n<robot name="r" _rd_src="0:1"><![CDATA[ _rd_src="0:1" ]]>'
             b'<link\n   name="a" _rd_src=\'0:2\'>text _rd_src="0:3"</link></robot>')
    assert strip_provenance(mixed) == (
        b'<?xml version="1.0"?>\n<robot name="r"><![CDATA[ _rd_src="0:1" ]]>'
        b'<link\n   name="a">text _rd_src="0:3"</link></robot>')


# -- refusals ---------------------------------------------------------------------------------

@pytest.mark.parametrize(("data", "line", "col"), [
    (b'<robot name="r">\n  <link name="a">\n</robot>\n', 3, 9),          # mismatched tag
    (b'<robot name="r">\n  <link name="a"/>\n  <joint name="j"', 3, 18),  # truncated
    (b"", 1, 1),                                                      # empty
    (b'<robot name="r"/>\n<robot name="s"/>', 2, 1),                  # two roots
    (b'<robot name="&undefined;"/>', 1, 27),                          # entity without DTD
])
def test_malformed_xml_names_path_line_and_column(data: bytes, line: int, col: int) -> None:
    with pytest.raises(XmlSyntaxError) as caught:
        parse_urdf(data, "bad.urdf")
    assert caught.value.span.path == "bad.urdf"
    assert caught.value.span.line == line
    assert caught.value.span.col > 0 and abs(caught.value.span.col - col) <= 2
    assert str(caught.value).startswith(f"bad.urdf:{line}:")
    assert not re.search(r"line \d+, column \d+$", caught.value.message)  # lxml's suffix


BILLION_LAUGHS = b"""<?xml version="1.0"?>
<!-- a comment before the DTD -->
<!DOCTYPE robot [
  <!ENTITY a "aaaaaaaaaa">
  <!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">
  <!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;">
  <!ENTITY d "&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;">
  <!ENTITY e "&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;">
  <!ENTITY f "&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;">
  <!ENTITY g "&f;&f;&f;&f;&f;&f;&f;&f;&f;&f;">
  <!ENTITY h "&g;&g;&g;&g;&g;&g;&g;&g;&g;&g;">
]>
<robot name="&h;"/>
"""


def test_doctype_billion_laughs_is_refused_before_any_xml_parser_sees_it(monkeypatch) -> None:
    import robotdesc.model.parse as parse_module

    def never(*args, **kwargs):
        raise AssertionError("the document reached lxml: its entities could have expanded")

    monkeypatch.setattr(parse_module.etree, "fromstring", never)
    with pytest.raises(XmlSyntaxError) as caught:
        parse_urdf(BILLION_LAUGHS, "lol.urdf")
    assert caught.value.span == Span("lol.urdf", 3)
    assert "DOCTYPE" in caught.value.message


def test_external_entity_is_refused_without_reading_the_file(tmp_path: Path) -> None:
    secret = tmp_path / "secret.txt"
    secret.write_text("TOPSECRET")
    data = (f'<!DOCTYPE robot [<!ENTITY xxe SYSTEM "file://{secret}">]>\n'
            '<robot name="r"><link name="&xxe;"/></robot>').encode()
    with pytest.raises(XmlSyntaxError) as caught:
        parse_urdf(data, "xxe.urdf")
    assert caught.value.span == Span("xxe.urdf", 1)
    assert "TOPSECRET" not in str(caught.value)


def test_doctype_text_inside_the_body_is_not_a_doctype() -> None:
    robot = parse_urdf(b'<robot name="r"><!-- <!DOCTYPE x> --><link name="a"/></robot>', "r.urdf")
    assert robot.links[0].name == "a"


def test_wrong_root_is_an_input_error_at_its_line() -> None:
    with pytest.raises(InputError) as caught:
        parse_urdf(b'<?xml version="1.0"?>\n\n<sdf version="1.7"/>', "model.sdf")
    assert not isinstance(caught.value, XmlSyntaxError)
    assert caught.value.span == Span("model.sdf", 3, 1)
    assert "<sdf>" in caught.value.message and "<robot>" in caught.value.message


# -- unreadable values ------------------------------------------------------------------------

BAD_VALUES = b"""<robot name="r">
  <link name="base">
    <inertial>
      <origin xyz="0 0.1"/>
      <mass value="heavy"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0"/>
    </inertial>
    <visual><geometry><box size="1 nan 1"/></geometry></visual>
    <collision><geometry><mesh filename="m.stl" scale="2"/></geometry></collision>
  </link>
  <joint name="j" type="revolute">
    <parent link="base"/><child link="arm"/>
    <limit lower="-1" upper="1" effort="abc" velocity="1_0"/>
    <mimic joint="k" multiplier="x"/>
  </joint>
  <link/>
</robot>
"""


def test_unreadable_values_become_defaults_and_issues() -> None:
    robot = parse_urdf(BAD_VALUES, "bad.urdf")
    base = robot.link("base")
    assert base.inertial.origin.xyz == (0.0, 0.0, 0.0)
    assert base.inertial.mass is None and base.inertial.inertia is None
    assert base.visuals[0].geometry is None
    assert base.collisions[0].geometry.scale == (1.0, 1.0, 1.0)
    joint = robot.joint("j")
    assert (joint.limit.lower, joint.limit.effort, joint.limit.velocity) == (-1.0, None, None)
    assert joint.mimic.joint == "k" and joint.mimic.multiplier is None
    assert robot.links[1].name == ""
    found = {(issue.element, issue.where.span.line, issue.message) for issue in robot.value_issues}
    assert found == {
        ("link:base", 4, '<origin> xyz="0 0.1" is not 3 numbers'),
        ("link:base", 5, '<mass> value="heavy" is not a number'),
        ("link:base", 6, "<inertia> izz is missing (required)"),
        ("link:base/visual[0]", 8, '<box> size="1 nan 1" is not 3 numbers'),
        ("link:base/collision[0]", 9, '<mesh> scale="2" is not 3 numbers'),
        ("joint:j", 13, '<limit> effort="abc" is not a number'),
        ("joint:j", 13, '<limit> velocity="1_0" is not a number'),
        ("joint:j", 14, '<mimic> multiplier="x" is not a number'),
        ("link:", 16, "<link> has no name (required)"),
    }


def test_missing_required_parts_are_issues() -> None:
    data = b"""<robot>
  <link name="a">
    <inertial><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <visual/>
    <collision><geometry><cone/></geometry></collision>
  </link>
  <joint name="j" type="continuous"><parent link="a"/><child link="b"/><limit/></joint>
</robot>"""
    robot = parse_urdf(data, "r.urdf")
    messages = {(i.where.span.line, i.message) for i in robot.value_issues}
    assert messages == {
        (1, "<robot> has no name (required)"),
        (3, "<inertial> has no <mass> (required)"),
        (4, "<geometry> is missing (required)"),
        (5, "<geometry> has an unknown shape <cone>"),
        (7, "<limit> effort is missing (required)"),
        (7, "<limit> velocity is missing (required)"),
    }
    assert robot.joints[0].limit.lower is None


# -- real robots ------------------------------------------------------------------------------

def _example_urdfs() -> list[Path]:
    return example_robot_urdfs()


EXAMPLES = _example_urdfs()


@pytest.mark.skipif(not EXAMPLES, reason="example-robot-data is not installed")
@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_example_robot_data_urdfs_parse(path: Path) -> None:
    robot = parse_urdf(path.read_bytes(), str(path))
    assert robot.links or path.name == "ur3.urdf"  # ur3.urdf is an empty, nameless robot
    for link in robot.links:
        assert link.where.span.path == str(path) and link.where.span.line > 0
    assert not [i for i in robot.value_issues if "robot" not in i.message], robot.value_issues


def _expanded_from(source: Path) -> bytes:
    return (f'<robot name="r" {PROVENANCE_ATTR}="0:1">'
            f'<link name="a" {PROVENANCE_ATTR}="0:2"><inertial {PROVENANCE_ATTR}="0:3">'
            f'<mass value="oops" {PROVENANCE_ATTR}="0:3"/></inertial></link>'
            f'<joint name="j" type="fixed" {PROVENANCE_ATTR}="0:4"><parent link="a"/>'
            f'<child link="b"/></joint><link name="b" {PROVENANCE_ATTR}="0:5"/>'
            "</robot>").encode()


def test_parses_with_one_file_table_share_unchanged_elements(tmp_path: Path) -> None:
    """The variants of a description and an editor's saves parse the same elements again:
    the second parse reuses the first one's (the same objects, the same value issues)."""
    source = tmp_path / "r.xacro"
    source.write_text('<robot name="r">\n<link name="a">\n<mass value="oops"/>\n'
                      '<joint name="j"/>\n<link name="b"/>\n</robot>\n')
    files = (str(source),)
    first = parse_urdf(_expanded_from(source), str(source), files)
    second = parse_urdf(_expanded_from(source), str(source), files)
    assert second.links[0] is first.links[0] and second.joints[0] is first.joints[0]
    assert second.value_issues == first.value_issues and len(first.value_issues) == 2
    changed = _expanded_from(source).replace(b'name="b"', b'name="c"')
    third = parse_urdf(changed, str(source), files)
    assert third.links[0] is first.links[0] and third.links[1].name == "c"


def test_a_shared_element_follows_an_edit_that_moves_its_column(tmp_path: Path) -> None:
    """An element whose bytes did not change is read again when its source line moved (its
    column comes from the source file)."""
    source = tmp_path / "r.xacro"
    source.write_text('<robot name="r">\n<link name="a">\n<mass value="oops"/>\n'
                      '<joint name="j"/>\n<link name="b"/>\n</robot>\n')
    files = (str(source),)
    before = parse_urdf(_expanded_from(source), str(source), files)
    assert before.links[1].where.span.col == 1
    source.write_text('<robot name="r">\n<link name="a">\n<mass value="oops"/>\n'
                      '<joint name="j"/>\n    <link name="b"/>\n</robot>\n')
    after = parse_urdf(_expanded_from(source), str(source), files)
    assert after.links[1].where.span.col == 5
