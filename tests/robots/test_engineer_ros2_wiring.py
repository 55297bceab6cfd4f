"""The Engineer's ROS 2 Jazzy + Gazebo Harmonic wiring, checked without ROS (issue 33): the
launch graph read with `ast` (which node gets which remapping, parameter, environment), the
controllers YAML against the URDF, the sensors and systems of the gz model, the bridge, the
resource path; the Gazebo Classic + ROS 1 side kept. libsdformat's converter (`gz sdf -p`)
checks the converted SDF where it is installed."""

from __future__ import annotations

import ast
import shutil
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

import pytest
import yaml
from lxml import etree

ROBOTS = Path(__file__).resolve().parents[2] / "robots"
DESCRIPTION, GAZEBO, CONTROL = (ROBOTS / n for n in ("engineer_description", "engineer_gazebo",
                                                     "engineer_control"))
GZ_TOP = GAZEBO / "urdf" / "engineer_gz.urdf.xacro"
CLASSIC_TOP = DESCRIPTION / "urdf" / "engineer.urdf.xacro"
SMALL = {"main_track_wheels": "4", "flipper_track_wheels": "3"}
#: ros2_controllers' Jazzy migration notes: diff_drive_controller no longer reads these.
REMOVED_IN_JAZZY = {"use_stamped_vel", "has_velocity_limits", "has_acceleration_limits",
                    "has_jerk_limits", "wheels_per_side"}


def _expand(top: Path, **args: str) -> etree._Element:
    from robotdesc.expansion import ExpandOptions, expand_file

    return etree.fromstring(expand_file(top, args, options=ExpandOptions(use_cache=False)).xml)


@pytest.fixture(scope="module")
def gz() -> etree._Element:
    return _expand(GZ_TOP, **SMALL)


@pytest.fixture(scope="module")
def classic() -> etree._Element:
    return _expand(CLASSIC_TOP, **SMALL)


# --- the launch graph, read with ast ---------------------------------------------------------


@dataclass
class Call:
    """A launch action as written: its class, its literal keyword values, where it sits."""

    kind: str
    keywords: dict[str, ast.expr]
    inside: list[str] = field(default_factory=list)

    def literal(self, name: str) -> object:
        try:
            return ast.literal_eval(self.keywords[name])
        except (KeyError, ValueError):
            return None


def _calls(path: Path) -> list[Call]:
    """Every call of a launch action class, with the classes of the calls around it."""
    found: list[Call] = []

    def visit(node: ast.AST, inside: list[str]) -> None:
        if isinstance(node, ast.Call):
            name = node.func.id if isinstance(node.func, ast.Name) else (
                node.func.attr if isinstance(node.func, ast.Attribute) else "")
            if name[:1].isupper():
                found.append(Call(name, {k.arg: k.value for k in node.keywords if k.arg},
                                  list(inside)))
                inside = [*inside, name]
        for child in ast.iter_child_nodes(node):
            visit(child, inside)

    visit(ast.parse(path.read_text(encoding="utf-8")), [])
    return found


def _nodes(path: Path) -> list[Call]:
    return [c for c in _calls(path) if c.kind == "Node"]


def test_no_spawner_gets_a_remapping():
    for path in (CONTROL / "launch" / "controllers.launch.py", GAZEBO / "launch" / "gz.launch.py"):
        for node in _nodes(path):
            if node.literal("executable") == "spawner":
                assert "remappings" not in node.keywords, path.name


def test_one_spawner_starts_every_controller_and_waits_for_the_manager():
    spawner, = [n for n in _nodes(CONTROL / "launch" / "controllers.launch.py")
                if n.literal("executable") == "spawner"]
    assert spawner.literal("package") == "controller_manager"
    arguments = ast.unparse(spawner.keywords["arguments"])
    assert "controller_names(with_gripper)" in arguments
    assert "--controller-manager-timeout" in arguments


def test_gz_launch_graph():
    calls = _calls(GAZEBO / "launch" / "gz.launch.py")
    nodes = {n.literal("executable"): n for n in calls if n.kind == "Node"}
    assert set(nodes) == {"robot_state_publisher", "create", "parameter_bridge"}
    publisher = ast.unparse(nodes["robot_state_publisher"].keywords["parameters"])
    assert "'robot_description'" in publisher and "'use_sim_time': True" in publisher
    assert nodes["create"].literal("arguments")[:2] == ["-topic", "robot_description"]
    assert "bridge.yaml" in ast.unparse(nodes["parameter_bridge"].keywords["parameters"])
    # the controllers are spawned when `create` has put the model into gz-sim
    handler, = [c for c in calls if c.kind == "OnProcessExit"]
    assert ast.unparse(handler.keywords["target_action"]) == "create"
    assert "spawners" in ast.unparse(handler.keywords["on_exit"])
    # gz-sim finds model://engineer_description through GZ_SIM_RESOURCE_PATH
    environment = [c for c in _calls(GAZEBO / "launch" / "gz.launch.py")
                   if c.kind == "AppendEnvironmentVariable"]
    assert environment
    source = (GAZEBO / "launch" / "gz.launch.py").read_text(encoding="utf-8")
    assert 'AppendEnvironmentVariable("GZ_SIM_RESOURCE_PATH", mesh_resource_path())' in source


def test_cmd_vel_is_remapped_on_the_controller_manager(gz):
    plugin, = gz.findall("gazebo/plugin[@filename='gz_ros2_control-system']")
    remaps = [r.text for r in plugin.findall("ros/remapping")]
    config = yaml.safe_load(Path(plugin.findtext("parameters")).read_text()) if \
        plugin.findtext("parameters") else None
    diff_drives = ["mobile_base_controller", "flipper_tracks_controller"]
    assert remaps == [f"/{name}/cmd_vel:=/cmd_vel" for name in diff_drives]
    assert config is None  # 4 + 3 wheels: no committed file; gz.launch.py passes one


def test_committed_controllers_files_are_named_for_their_counts():
    for (main, flipper), name in {("56", "50"): "engineer_ros2_controllers.yaml",
                                  ("18", "31"): "engineer_ros2_controllers_18_31.yaml"}.items():
        root = _expand(GZ_TOP, main_track_wheels=main, flipper_track_wheels=flipper,
                       with_gripper="false")
        named = Path(root.findtext("gazebo/plugin/parameters"))
        assert named == CONTROL / "config" / name
        config = yaml.safe_load(named.read_text())
        joints = {j.get("name") for j in root.findall("joint")}
        wheels = config["mobile_base_controller"]["ros__parameters"]["left_wheel_names"]
        assert len(wheels) == int(main) and set(wheels) <= joints


def test_ros2_controllers_yaml_is_jazzy_and_matches_the_urdf(gz):
    config = yaml.safe_load((CONTROL / "config" / "engineer_ros2_controllers.yaml").read_text())
    manager = config["controller_manager"]["ros__parameters"]
    for name, params in config.items():
        if name == "controller_manager":
            continue
        assert name in manager, name
        keys = {key.rsplit(".", 1)[-1] for key in params["ros__parameters"]}
        assert not keys & REMOVED_IN_JAZZY, name
    joints = {j.get("name"): j for j in gz.findall("joint")}
    for name in ("arm_controller", "flippers_controller", "gripper_controller"):
        params = config[name]["ros__parameters"]
        assert params["command_interfaces"] == ["effort"]
        for joint in params["joints"]:
            assert joints[joint].find("mimic") is None
            declared = gz.find(f"ros2_control/joint[@name='{joint}']")
            assert declared.find("command_interface").get("name") == "effort"


def test_mimic_joints_follow_the_urdf_in_ros2_control(gz):
    for joint in gz.findall("ros2_control/joint"):
        urdf = gz.find(f"joint[@name='{joint.get('name')}']")
        if urdf.find("mimic") is not None:
            assert joint.find("command_interface") is None
            assert joint.find("param") is None


# --- sensors, systems, bridge, resource path -------------------------------------------------


def test_gz_model_sensors_and_systems(gz):
    lrf = gz.find("gazebo[@reference='lrf_link']/sensor")
    assert lrf.get("type") == "gpu_lidar" and lrf.find("lidar") is not None
    assert lrf.findtext("topic") == "scan"
    assert gz.find("gazebo[@reference='imu_link']/sensor").get("type") == "imu"
    model_plugins = [p.get("name") for p in gz.findall("gazebo/plugin")]
    assert model_plugins == ["gz_ros2_control::GazeboSimROS2ControlPlugin"]
    assert not [p for p in gz.iter("plugin") if p.get("filename", "").startswith("lib")]


def test_world_loads_the_world_systems_once():
    world = etree.parse(str(GAZEBO / "worlds" / "empty.sdf")).getroot()
    names = [p.get("name") for p in world.findall("world/plugin")]
    for system in ("Sensors", "Imu"):
        assert names.count(f"gz::sim::systems::{system}") == 1


def test_bridge_carries_every_gz_sensor_topic(gz):
    entries = yaml.safe_load((GAZEBO / "config" / "bridge.yaml").read_text())
    bridged = {e["gz_topic_name"]: e["gz_type_name"] for e in entries}
    for sensor in gz.iter("sensor"):
        topic = sensor.findtext("topic")
        if sensor.get("type") == "camera":
            folder = topic.rsplit("/", 1)[0]
            assert bridged[topic] == "gz.msgs.Image"
            assert bridged[f"{folder}/camera_info"] == "gz.msgs.CameraInfo"
        elif sensor.get("type") == "gpu_lidar":
            assert bridged[topic] == "gz.msgs.LaserScan"
        elif sensor.get("type") == "imu":
            assert bridged[topic] == "gz.msgs.IMU"
    assert bridged["/clock"] == "gz.msgs.Clock"


def test_description_exports_its_share_folder_to_gz_sim():
    cmake = (DESCRIPTION / "CMakeLists.txt").read_text()
    assert 'ament_environment_hooks("${CMAKE_CURRENT_SOURCE_DIR}/hooks/${PROJECT_NAME}.dsv.in")' \
        in cmake
    hook = (DESCRIPTION / "hooks" / "engineer_description.dsv.in").read_text().split()
    assert hook == ["prepend-non-duplicate;GZ_SIM_RESOURCE_PATH;share"]


# --- Gazebo Classic + ROS 1 ------------------------------------------------------------------


def test_classic_keeps_its_plugins_and_ros1_relays(classic):
    assert classic.find("gazebo[@reference='lrf_link']/sensor").get("type") == "ray"
    filenames = {p.get("filename") for p in classic.iter("plugin")}
    assert {"libgazebo_ros_control.so", "libgazebo_ros_laser.so",
            "libroboticsgroup_upatras_gazebo_mimic_joint_plugin.so"} <= filenames
    depends = {e.text for e in etree.parse(str(GAZEBO / "package.xml")).getroot().iter(
        "exec_depend") if e.get("condition") == "$ROS_VERSION == 1"}
    assert "roboticsgroup_upatras_gazebo_plugins" in depends
    launch = etree.parse(str(CONTROL / "launch" / "engineer_control.launch")).getroot()
    relays = [n.get("args") for n in launch.iter("node") if n.get("type") == "relay"]
    assert relays == ["/cmd_vel mobile_base_controller/cmd_vel",
                      "/cmd_vel flipper_tracks_controller/cmd_vel"]


# --- libsdformat's converter, where installed ------------------------------------------------

GZ = shutil.which("gz") or shutil.which("ign")


@pytest.mark.skipif(GZ is None, reason="libsdformat's URDF->SDF converter (`gz sdf -p`, from "
                    "gz-tools with libsdformat) is not installed")
def test_converted_sdf_has_gz_sensors_and_systems(tmp_path, gz):
    urdf = tmp_path / "engineer_gz.urdf"
    urdf.write_bytes(etree.tostring(gz))
    converted = subprocess.run([GZ, "sdf", "-p", str(urdf)], capture_output=True, check=True,
                               timeout=120).stdout
    sdf = etree.fromstring(converted)
    types = {s.get("name"): s.get("type") for s in sdf.iter("sensor")}
    assert types["lrf"] == "gpu_lidar" and types["imu_sensor"] == "imu"
    assert [types[f"camera_{n}"] for n in range(1, 5)] == ["camera"] * 4
    systems = [p.get("name") for p in sdf.find("model").findall("plugin")]
    assert systems == ["gz_ros2_control::GazeboSimROS2ControlPlugin"]
