"""A large generated robot (212 wheels) with every element kind is clean under all rules."""

from __future__ import annotations

from robotdesc.model.parse import parse_urdf
from robotdesc.rules.catalog import all_rules
from robotdesc.rules.registry import RuleContext, run_rule


def many_wheeled_robot(wheels: int) -> bytes:
    """A rover with `wheels` wheels, each with a mesh visual, a transmission and gazebo tags."""
    parts = ['<robot name="rover">', '<material name="black"><color rgba="0 0 0 1"/></material>',
             ('<link name="base_link"><inertial><mass value="100"/>'
             '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>')]
    for i in range(wheels):
        parts.append(
            f'<link name="wheel_{i}"><inertial><origin xyz="0 0 0"/><mass value="1"/>'
            '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>'
            '<visual><origin xyz="0 0 0" rpy="1.5708 0 0"/>'
            '<geometry><mesh filename="package://rover/meshes/wheel.stl"/></geometry>'
            '<material name="black"/></visual>'
            '<collision><geometry><cylinder radius="0.1" length="0.05"/></geometry></collision>'
            '</link>'
            f'<joint name="wheel_{i}_joint" type="continuous"><origin xyz="{i * 0.3} 0.5 0"/>'
            f'<parent link="base_link"/><child link="wheel_{i}"/><axis xyz="0 1 0"/>'
            '<limit effort="10" velocity="20"/><dynamics damping="0.1"/></joint>'
            f'<transmission name="wheel_{i}_trans">'
            '<type>transmission_interface/SimpleTransmission</type>'
            f'<joint name="wheel_{i}_joint"><hardwareInterface>hardware_interface/'
            'VelocityJointInterface</hardwareInterface></joint>'
            f'<actuator name="wheel_{i}_motor"><mechanicalReduction>1</mechanicalReduction>'
            '</actuator></transmission>'
            f'<gazebo reference="wheel_{i}"><mu1>1.0</mu1></gazebo>')
    parts.append("</robot>")
    return "\n".join(parts).encode()


def lint_all(data: bytes) -> list:
    robot = parse_urdf(data, "rover.urdf")
    return [f for r in all_rules()
            for f in run_rule(r, robot, RuleContext(options=r.default_options()))]


def test_212_wheel_robot_is_clean_under_every_rule() -> None:
    """Speed of this case is measured in benchmarks/bench_parse_rules.py, not asserted here."""
    assert lint_all(many_wheeled_robot(212)) == []
