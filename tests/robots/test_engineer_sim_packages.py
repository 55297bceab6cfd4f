"""engineer_gazebo and engineer_control: xacro, lint, controller YAML against the URDF's joints,
launch files importable without ROS, and no link Gazebo's URDF->SDF converter would drop."""

from __future__ import annotations

import importlib.util
import sys
import types
from pathlib import Path

import pytest
from lxml import etree

ROBOTS = Path(__file__).resolve().parents[2] / "robots"
DESCRIPTION, GAZEBO, CONTROL = (ROBOTS / n for n in ("engineer_description", "engineer_gazebo",
                                                     "engineer_control"))
TOPS = {"description": DESCRIPTION / "urdf" / "engineer.urdf.xacro",
        "gz": GAZEBO / "urdf" / "engineer_gz.urdf.xacro"}


def _expand(top: Path, **args) -> etree._Element:
    from robotdesc.expansion import ExpandOptions, expand_file

    return etree.fromstring(expand_file(top, {k: str(v) for k, v in args.items()},
                                        options=ExpandOptions(use_cache=False)).xml)


@pytest.fixture(scope="module")
def make_controllers():
    sys.path.insert(0, str(CONTROL / "scripts"))
    try:
        yield importlib.import_module("make_controllers")
    finally:
        sys.path.remove(str(CONTROL / "scripts"))


def _targets(package: Path):
    import tomllib

    with open(package / "robotdesc.toml", "rb") as stream:
        return [(package / t["file"], t.get("args", {})) for t in tomllib.load(stream)["targets"]]


@pytest.mark.slow
@pytest.mark.parametrize("package", [DESCRIPTION, GAZEBO], ids=lambda p: p.name)
def test_every_listed_variant_expands_and_lints_clean(package):
    import robotdesc

    for top, args in _targets(package):
        assert _expand(top, **args).tag == "robot"
        result = robotdesc.lint(str(top), args=args)
        assert [f"{d.code} {d.message}" for d in result.diagnostics] == [], (top.name, args)


def _sdformat_dropped(root) -> list[str]:
    """Links libsdformat's URDF->SDF converter drops: a non-root link without an <inertial>
    (or with zero mass) that has child joints, and everything under it."""
    children: dict[str, list] = {}
    parents = set()
    for joint in root.findall("joint"):
        children.setdefault(joint.find("parent").get("link"), []).append(joint)
        parents.add(joint.find("child").get("link"))
    dropped = []
    for link in root.findall("link"):
        mass = link.find("inertial/mass")
        massless = mass is None or float(mass.get("value")) == 0.0
        is_root = link.get("name") not in parents
        moving = [j for j in children.get(link.get("name"), []) if j.get("type") != "fixed"]
        if massless and not is_root and moving:
            dropped.append(link.get("name"))
    return dropped


@pytest.mark.parametrize("top", list(TOPS), ids=str)
@pytest.mark.parametrize("args", [{}, {"with_gripper": "false"}], ids=["gripper", "no_gripper"])
def test_gazebo_converter_keeps_every_link(top, args):
    root = _expand(TOPS[top], main_track_wheels=3, flipper_track_wheels=2, **args)
    assert _sdformat_dropped(root) == []
    if not args:
        base = root.find("link[@name='gripper_base_link']/inertial/mass")
        assert base is not None and float(base.get("value")) > 0


def test_the_check_would_catch_the_old_gripper_base():
    root = _expand(TOPS["description"], main_track_wheels=1, flipper_track_wheels=1)
    root.find("link[@name='gripper_base_link']").remove(
        root.find("link[@name='gripper_base_link']/inertial"))
    assert _sdformat_dropped(root) == ["gripper_base_link"]


@pytest.mark.parametrize("main,flipper", [(56, 50), (18, 31), (4, 3), (1, 0)])
def test_controller_yaml_names_the_urdf_joints(make_controllers, main, flipper):
    yaml = pytest.importorskip("yaml")
    root = _expand(TOPS["gz"], main_track_wheels=main, flipper_track_wheels=flipper)
    joints = {j.get("name"): j for j in root.findall("joint")}
    wheels = {n for n, j in joints.items() if j.get("type") == "continuous"}
    # ROS 1
    ros1 = yaml.safe_load(make_controllers.ros1_tracks_yaml(main, flipper))
    named = set()
    for block in ros1.values():
        named |= set(block["left_wheel"]) | set(block["right_wheel"])
    assert named == wheels
    gains = yaml.safe_load((CONTROL / "config" / "engineer_control.yaml").read_text())
    for block in gains.values():
        if "joint" in block:
            assert block["joint"] in joints and joints[block["joint"]].find("mimic") is None
            assert block["pid"]["i_clamp"] > 0
    for follower in gains["gazebo_ros_control"]["pid_gains"]:
        assert joints[follower].find("mimic") is not None
    # ROS 2
    ros2 = yaml.safe_load(make_controllers.ros2_yaml(main, flipper))
    listed = set(ros2["controller_manager"]["ros__parameters"]) - {"update_rate"}
    assert set(ros2) - {"controller_manager"} <= listed
    named = set()
    for name in listed:
        params = ros2[name]["ros__parameters"] if name in ros2 else {}
        named |= set(params.get("left_wheel_names", [])) | set(params.get("right_wheel_names", []))
        for joint in params.get("joints", []):
            assert joint in joints and joints[joint].find("mimic") is None
            assert params["gains"][joint]["i_clamp"] > 0
    assert named == wheels
    # <ros2_control> declares every wheel and driven joint, mimics as mimics
    system = root.find("ros2_control")
    declared = {j.get("name"): j for j in system.findall("joint")}
    moving = {n for n, j in joints.items() if j.get("type") != "fixed"}
    assert set(declared) == moving
    for name, joint in declared.items():
        is_mimic = joints[name].find("mimic") is not None
        # Jazzy's ros2_control takes the mimic from the URDF: no Humble-era <param name="mimic">
        assert joint.find("param[@name='mimic']") is None, name
        assert (joint.find("command_interface") is None) == is_mimic, name


def _stub_ros_modules(monkeypatch):
    """Minimal stand-ins for launch and launch_ros: enough to import and call the launch files."""

    class Thing:
        def __init__(self, *args, **kwargs):
            self.args, self.kwargs = args, kwargs

    class LaunchDescription(Thing):
        @property
        def entities(self):
            return list(self.args[0]) if self.args else []

    modules = {
        "launch": {"LaunchDescription": LaunchDescription},
        "launch.actions": {n: type(n, (Thing,), {}) for n in (
            "AppendEnvironmentVariable", "DeclareLaunchArgument", "IncludeLaunchDescription",
            "OpaqueFunction", "RegisterEventHandler")},
        "launch.event_handlers": {"OnProcessExit": Thing},
        "launch.substitutions": {n: type(n, (Thing,), {}) for n in (
            "Command", "LaunchConfiguration", "PathJoinSubstitution")},
        "launch.launch_description_sources": {"PythonLaunchDescriptionSource": Thing},
        "launch_ros": {},
        "launch_ros.actions": {"Node": type("Node", (Thing,), {})},
        "launch_ros.parameter_descriptions": {"ParameterValue": Thing},
        "launch_ros.substitutions": {"FindPackageShare": Thing},
        "ament_index_python": {},
        "ament_index_python.packages": {
            "get_package_share_directory": lambda name: str(ROBOTS / name)},
    }
    for name, attrs in modules.items():
        module = types.ModuleType(name)
        module.__dict__.update(attrs)
        monkeypatch.setitem(sys.modules, name, module)


@pytest.mark.parametrize("path", [DESCRIPTION / "launch" / "display.launch.py",
                                  CONTROL / "launch" / "controllers.launch.py",
                                  GAZEBO / "launch" / "gz.launch.py"], ids=lambda p: p.name)
def test_launch_files_import_without_ros(monkeypatch, path):
    _stub_ros_modules(monkeypatch)
    spec = importlib.util.spec_from_file_location(f"launch_{path.stem.replace('.', '_')}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    description = module.generate_launch_description()
    assert type(description).__name__ == "LaunchDescription"
    assert description.entities


def test_controllers_launch_writes_a_file_for_any_wheel_count(monkeypatch):
    yaml = pytest.importorskip("yaml")
    _stub_ros_modules(monkeypatch)
    path = CONTROL / "launch" / "controllers.launch.py"
    spec = importlib.util.spec_from_file_location("controllers_launch", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    written = Path(module.controllers_file_for("7", "5"))
    try:
        config = yaml.safe_load(written.read_text())
        assert len(config["mobile_base_controller"]["ros__parameters"]["left_wheel_names"]) == 7
        assert len(config["flipper_tracks_controller"]["ros__parameters"]["right_wheel_names"]) == 5
    finally:
        written.unlink()


@pytest.mark.parametrize("launch", [CONTROL / "launch" / "engineer_control.launch",
                                    GAZEBO / "launch" / "engineer_world.launch"], ids=lambda p: p.name)
def test_ros1_launch_files_are_xml_with_their_files(launch):
    root = etree.parse(str(launch)).getroot()
    assert root.tag == "launch"
    text = launch.read_text()
    for package, folder in ((CONTROL, "config"), (GAZEBO, "launch")):
        for name in (n.split(")/")[-1] for n in text.split("$(find ")[1:] if n.startswith(package.name)):
            relative = name.split('"')[0].split()[0]
            assert (package / relative).exists() or not relative.startswith(folder), relative


def test_imu_publishes_at_100_hz():
    root = _expand(TOPS["description"], main_track_wheels=1, flipper_track_wheels=1)
    sensor = root.find("gazebo[@reference='imu_link']/sensor")
    assert float(sensor.findtext("update_rate")) == 100.0
    assert float(sensor.findtext("plugin/updateRateHZ")) == 100.0
