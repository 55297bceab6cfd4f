"""R1xx (ros2): each rule on small descriptions and package files, and the real-world cases
that must stay silent. The Engineer's packages before and after issue 33:
test_ros2_wiring_engineer.py."""

from __future__ import annotations

import pytest

from robotdesc.model.parse import parse_urdf
from robotdesc.rules.catalog import get_rule
from robotdesc.rules.package_files import (
    CMAKE,
    HOOK,
    LAUNCH_PY,
    LAUNCH_XML,
    MANIFEST,
    WORLD,
    YAML,
    Package,
    PackageFile,
    PackageFiles,
)
from robotdesc.rules.registry import RuleContext, SourceDocument, run_rule
from robotdesc.rules.ros2 import RemovedParameterOptions

ARM = """<robot name="arm">
  <link name="base"/><link name="upper"/><link name="tool"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
  <joint name="flange" type="fixed"><parent link="upper"/><child link="tool"/></joint>
  <link name="wheel_link"/>
  <joint name="wheel" type="continuous"><parent link="base"/><child link="wheel_link"/></joint>
  {extra}
</robot>"""

GZ_CONTROL = """<gazebo><plugin filename="gz_ros2_control-system"
  name="gz_ros2_control::GazeboSimROS2ControlPlugin"/></gazebo>"""


def _findings(code: str, urdf: str, package: PackageFiles | None = None,
              options: object = None) -> list[str]:
    rule_ = get_rule(code)
    assert rule_ is not None
    xml = urdf.encode()
    ctx = RuleContext(options=options or rule_.default_options(),
                      document=SourceDocument(xml, "robot.urdf"), package=package)
    return [f.message for f in run_rule(rule_, parse_urdf(xml, "robot.urdf"), ctx)]


def _package(*files: tuple[str, str, str], named: tuple[PackageFile, ...] = ()) -> PackageFiles:
    """One package `pkg` at /ws/pkg with (relative path, kind, text) files."""
    return PackageFiles((Package("pkg", "/ws/pkg", tuple(
        PackageFile(f"/ws/pkg/{path}", kind, text) for path, kind, text in files)),), named)


# --- R101, R102: <ros2_control> -------------------------------------------------------------


def test_r101_unknown_joint_with_a_hint():
    extra = """<ros2_control name="s" type="system"><hardware><plugin>x</plugin></hardware>
      <joint name="shouldr"><command_interface name="position"/></joint>
      <joint name="shoulder"><command_interface name="position"/></joint></ros2_control>"""
    assert _findings("R101", ARM.format(extra=extra)) == [
        "<ros2_control> joint 'shouldr' is not a joint of the robot; did you mean 'shoulder'?"]


def test_r101_sensors_and_gpio_are_not_joints():
    extra = """<ros2_control name="s" type="system"><hardware><plugin>x</plugin></hardware>
      <sensor name="ft"><state_interface name="force.x"/></sensor>
      <gpio name="io"><command_interface name="out"/></gpio></ros2_control>"""
    assert _findings("R101", ARM.format(extra=extra)) == []


def test_r102_fixed_joint_and_misspelt_interface():
    extra = """<ros2_control name="s" type="system"><hardware><plugin>x</plugin></hardware>
      <joint name="flange"><state_interface name="position"/></joint>
      <joint name="shoulder"><command_interface name="Position"/></joint>
      <joint name="wheel"><command_interface name="velocty"/></joint></ros2_control>"""
    found = _findings("R102", ARM.format(extra=extra))
    assert len(found) == 3
    assert "'flange' is fixed" in found[0]
    assert "did you mean 'position'" in found[1] and "did you mean 'velocity'" in found[2]


def test_r102_custom_hardware_interfaces_stay_silent():
    extra = """<ros2_control name="s" type="system"><hardware><plugin>x</plugin></hardware>
      <joint name="shoulder"><command_interface name="current"/>
        <state_interface name="temperature"/><state_interface name="position"/></joint>
      <joint name="wheel"><command_interface name="velocity"/></joint></ros2_control>"""
    assert _findings("R102", ARM.format(extra=extra)) == []


# --- R104, R105: plugins and sensors --------------------------------------------------------


def test_r104_gz_class_with_classic_library_and_the_reverse():
    extra = """<gazebo>
      <plugin filename="libgazebo_ros2_control.so" name="gz_ros2_control::GazeboSimROS2ControlPlugin"/>
      <plugin filename="gz-sim-imu-system" name="imu_plugin"/></gazebo>"""
    found = _findings("R104", ARM.format(extra=extra))
    assert len(found) == 2
    assert "Gazebo Classic library" in found[0] and "not a system class" in found[1]


def test_r104_matching_names_stay_silent():
    extra = """<gazebo>
      <plugin filename="libgazebo_ros2_control.so" name="gazebo_ros2_control"/>
      <plugin filename="gz-sim-joint-state-publisher-system"
              name="gz::sim::systems::JointStatePublisher"/>
      <plugin filename="ignition-gazebo-imu-system" name="ignition::gazebo::systems::Imu"/>
      <plugin filename="libgazebo_ros_p3d.so" name="p3d"/></gazebo>"""
    assert _findings("R104", ARM.format(extra=extra)) == []


LASER = """<gazebo reference="tool"><sensor type="ray" name="laser"><ray/></sensor></gazebo>"""


def test_r105_ray_sensor_under_gz_sim():
    found = _findings("R105", ARM.format(extra=LASER + GZ_CONTROL))
    assert len(found) == 1 and "gpu_lidar" in found[0]


@pytest.mark.parametrize("extra", [
    LASER,  # Gazebo Classic only
    LASER + """<gazebo><plugin filename="libgazebo_ros2_control.so" name="gazebo_ros2_control"/>
              </gazebo>""",
    LASER.replace('"ray"', '"gpu_lidar"') + GZ_CONTROL,
], ids=["classic", "classic-ros2-control", "gpu-lidar"])
def test_r105_silent(extra):
    assert _findings("R105", ARM.format(extra=extra)) == []


# --- R103: controllers YAML -----------------------------------------------------------------

CONTROLLERS = """controller_manager:
  ros__parameters:
    update_rate: 100
arm_controller:
  ros__parameters:
    joints: [shoulder, elbow]
    command_interfaces: [position]
other_robot_controller:
  ros__parameters:
    joints: [joint_a, joint_b]
"""


def test_r110_controller_of_the_package_naming_a_missing_joint():
    package = _package(("config/controllers.yaml", YAML, CONTROLLERS))
    found = _findings("R110", ARM.format(extra=""), package)
    assert found == ["controller 'arm_controller' names 'elbow', not joints of the robot"]
    assert _findings("R103", ARM.format(extra=""), package) == []  # not named: R110's


def test_r110_is_opt_in():
    rule_ = get_rule("R110")
    assert rule_ is not None and rule_.opt_in


def test_r103_named_file_outside_the_package():
    named = (PackageFile("/elsewhere/c.yaml", YAML, CONTROLLERS),)
    found = _findings("R103", ARM.format(extra=""), _package(named=named))
    assert len(found) == 1


def test_r103_yaml_of_a_used_package_that_is_not_named_is_not_judged():
    package = PackageFiles((Package("robot_description", "/ws/d"),
                            Package("pkg", "/ws/pkg", (
                                PackageFile("/ws/pkg/c.yaml", YAML, CONTROLLERS),))))
    assert _findings("R103", ARM.format(extra=""), package) == []


def test_r110_ros1_controllers_and_bad_yaml():
    ros1 = "base:\n  type: diff_drive_controller/DiffDriveController\n  left_wheel: wheel\n" \
           "  right_wheel: [wheel, right_wheel]\n"
    package = _package(("config/a.yaml", YAML, ros1), ("config/b.yaml", YAML, "a: [b\n"))
    found = _findings("R110", ARM.format(extra=""), package)
    assert found == ["controller 'base' names 'right_wheel', not joints of the robot"]


# --- R106: world-wide systems ----------------------------------------------------------------

WORLD_SDF = """<?xml version="1.0"?><sdf version="1.8"><world name="w">
  <plugin filename="gz-sim-sensors-system" name="gz::sim::systems::Sensors"/>
  <plugin filename="gz-sim-imu-system" name="gz::sim::systems::Imu"/>
</world></sdf>"""


def test_r106_imu_loaded_by_model_and_world():
    extra = """<gazebo><plugin filename="gz-sim-imu-system" name="gz::sim::systems::Imu"/>
      <plugin filename="gz-sim-contact-system" name="gz::sim::systems::Contact"/></gazebo>"""
    package = _package(("worlds/w.sdf", WORLD, WORLD_SDF))
    found = _findings("R106", ARM.format(extra=extra), package)
    assert found == ["the world-wide system Imu is loaded by the robot and by the world "
                     "pkg/worlds/w.sdf: every imu message comes twice"]


def test_r106_silent_without_a_world_that_loads_it():
    extra = """<gazebo><plugin filename="gz-sim-imu-system" name="gz::sim::systems::Imu"/>
      </gazebo>"""
    world = WORLD_SDF.replace("imu", "user-commands").replace("Imu", "UserCommands")
    assert _findings("R106", ARM.format(extra=extra), _package(("w.world", WORLD, world))) == []


# --- R107: GZ_SIM_RESOURCE_PATH --------------------------------------------------------------

MESHED = ARM.replace('<link name="upper"/>', """<link name="upper"><visual><geometry>
  <mesh filename="package://pkg/meshes/upper.stl"/></geometry></visual></link>""")


def test_r107_package_meshes_without_a_resource_path():
    launch = "from launch import LaunchDescription\n# GZ_SIM_RESOURCE_PATH is set by hand\n"
    package = _package(("launch/sim.launch.py", LAUNCH_PY, launch),
                       ("package.xml", MANIFEST, "<package><name>pkg</name></package>"))
    found = _findings("R107", MESHED.format(extra=GZ_CONTROL), package)
    assert len(found) == 1 and "'package://pkg/meshes/upper.stl'" in found[0]


@pytest.mark.parametrize("files", [
    (("hooks/pkg.dsv.in", HOOK, "prepend-non-duplicate;GZ_SIM_RESOURCE_PATH;share"),),
    (("package.xml", MANIFEST,
      '<package><export><gazebo_ros gazebo_model_path="${prefix}/.."/></export></package>'),),
    (("launch/sim.launch.py", LAUNCH_PY,
      'AppendEnvironmentVariable("GZ_SIM_RESOURCE_PATH", share)\n'),),
    (("launch/sim.launch.xml", LAUNCH_XML,
      '<launch><set_env name="IGN_GAZEBO_RESOURCE_PATH" value="x"/></launch>'),),
    (("CMakeLists.txt", CMAKE, 'ament_environment_hooks("GZ_SIM_RESOURCE_PATH.dsv")'),),
], ids=["hook", "package-xml", "launch-py", "launch-xml", "cmake"])
def test_r107_silent_when_exported(files):
    assert _findings("R107", MESHED.format(extra=GZ_CONTROL), _package(*files)) == []


def test_r107_silent_for_classic_and_for_packages_not_read():
    assert _findings("R107", MESHED.format(extra=""), _package()) == []
    other = MESHED.replace("package://pkg/", "package://other_pkg/")
    assert _findings("R107", other.format(extra=GZ_CONTROL), _package()) == []


# --- R108: Jazzy-removed parameters ----------------------------------------------------------

DIFF_DRIVE = """base_controller:
  ros__parameters:
    left_wheel_names: [wheel]
    right_wheel_names: [wheel]
    use_stamped_vel: false
    linear:
      x:
        has_velocity_limits: true
        max_velocity: 1.0
    angular.z.has_jerk_limits: false
"""
HARMONIC_SENSOR = """<gazebo reference="tool"><sensor type="imu" name="imu">
  <gz_frame_id>tool</gz_frame_id></sensor></gazebo>"""


def test_r108_removed_parameters_under_harmonic_names():
    package = _package(("config/c.yaml", YAML, DIFF_DRIVE))
    found = _findings("R108", ARM.format(extra=HARMONIC_SENSOR), package)
    assert [m.split("'")[3] for m in found] == [
        "use_stamped_vel", "linear.x.has_velocity_limits", "angular.z.has_jerk_limits"]


def test_r108_distro_option():
    package = _package(("config/c.yaml", YAML, DIFF_DRIVE))
    assert _findings("R108", ARM.format(extra=""), package) == []  # nothing says Jazzy
    assert len(_findings("R108", ARM.format(extra=""), package,
                         RemovedParameterOptions(distro="jazzy"))) == 3
    assert _findings("R108", ARM.format(extra=HARMONIC_SENSOR), package,
                     RemovedParameterOptions(distro="humble")) == []


def test_r108_ros1_diff_drive_keeps_its_flags():
    ros1 = "base:\n  type: diff_drive_controller/DiffDriveController\n  left_wheel: wheel\n" \
           "  right_wheel: wheel\n  linear:\n    x:\n      has_velocity_limits: true\n"
    package = _package(("config/c.yaml", YAML, ros1))
    assert _findings("R108", ARM.format(extra=HARMONIC_SENSOR), package) == []


# --- R109: remaps on spawners ----------------------------------------------------------------

SPAWNER_PY = '''from launch_ros.actions import Node
def generate_launch_description():
    base = Node(package="controller_manager", executable="spawner",
                arguments=["base_controller"],
                remappings=[("/base_controller/cmd_vel", "/cmd_vel")])
    manager = Node(package="controller_manager", executable="ros2_control_node",
                   remappings=[("/base_controller/cmd_vel", "/cmd_vel")])
    plain = Node(package="controller_manager", executable="spawner", arguments=["jsb"],
                 remappings=[])
    return [base, manager, plain]
'''
SPAWNER_XML = """<launch><group ns="r">
  <node name="spawner" pkg="controller_manager" type="spawner" args="base">
    <remap from="cmd_vel" to="/cmd_vel"/></node>
  <node name="relay" pkg="topic_tools" type="relay" args="/cmd_vel base/cmd_vel"/>
</group></launch>"""


def test_r109_remaps_on_spawners_python_and_xml():
    package = _package(("launch/a.launch.py", LAUNCH_PY, SPAWNER_PY),
                       ("launch/b.launch", LAUNCH_XML, SPAWNER_XML))
    rule_ = get_rule("R109")
    assert rule_ is not None
    xml = ARM.format(extra="").encode()
    findings = list(run_rule(rule_, parse_urdf(xml, "r.urdf"), RuleContext(package=package)))
    assert [(f.where.span.path, f.where.span.line) for f in findings if f.where] == [
        ("/ws/pkg/launch/a.launch.py", 3), ("/ws/pkg/launch/b.launch", 2)]


def test_r109_launch_file_that_does_not_parse_is_skipped():
    package = _package(("launch/a.launch.py", LAUNCH_PY, "def broken(:\n"))
    assert _findings("R109", ARM.format(extra=""), package) == []


@pytest.mark.parametrize("code", ["R103", "R106", "R107", "R108", "R109", "R110"])
def test_package_rules_are_silent_outside_a_lint(code):
    assert _findings(code, ARM.format(extra=GZ_CONTROL)) == []
