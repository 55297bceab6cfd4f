"""ROS 2 + gz-sim: start gz-sim, spawn the Engineer (engineer_gz.urdf.xacro, with
<ros2_control> and gz_ros2_control), bridge its sensors and start its controllers.

ros2 launch engineer_gazebo gz.launch.py [main_track_wheels:=56] [flipper_track_wheels:=50]
                                         [with_gripper:=true] [world:=empty.sdf]

ROS 2 Jazzy + Gazebo Harmonic. gz-sim finds the meshes (package://engineer_description/...
becomes model://engineer_description/...) through GZ_SIM_RESOURCE_PATH, which this file
extends by the share folder holding engineer_description (its environment hook does the same
for a sourced workspace). The controllers are spawned once the model is in gz-sim.
"""

import os

from launch import LaunchDescription
from launch.actions import (
    AppendEnvironmentVariable,
    DeclareLaunchArgument,
    IncludeLaunchDescription,
    OpaqueFunction,
    RegisterEventHandler,
)
from launch.event_handlers import OnProcessExit
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare

ARGS = {"main_track_wheels": "56", "flipper_track_wheels": "50", "with_gripper": "true",
        "world": "empty.sdf"}


def _load_controllers_module():
    """engineer_control's launch module (its controllers file writer and spawners)."""
    import importlib.util

    from ament_index_python.packages import get_package_share_directory

    path = os.path.join(get_package_share_directory("engineer_control"), "launch",
                        "controllers.launch.py")
    spec = importlib.util.spec_from_file_location("engineer_controllers_launch", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def robot_description(share_gazebo, args, controllers_file):
    """The xacro command line of the gz model for these arguments."""
    return " ".join(["xacro", os.path.join(share_gazebo, "urdf", "engineer_gz.urdf.xacro"),
                     *(f"{k}:={args[k]}" for k in ("main_track_wheels", "flipper_track_wheels",
                                                   "with_gripper")),
                     f"controllers_file:={controllers_file}"])


def _setup(context):
    from ament_index_python.packages import get_package_share_directory
    from launch.substitutions import Command
    from launch_ros.parameter_descriptions import ParameterValue

    args = {name: LaunchConfiguration(name).perform(context) for name in ARGS}
    controllers = _load_controllers_module()
    controllers_file = controllers.controllers_file_for(args["main_track_wheels"],
                                                        args["flipper_track_wheels"])
    share = get_package_share_directory("engineer_gazebo")
    description = ParameterValue(Command(robot_description(share, args, controllers_file)),
                                 value_type=str)
    create = Node(package="ros_gz_sim", executable="create", output="screen",
                  arguments=["-topic", "robot_description", "-name", "engineer", "-z", "0.02"])
    return [
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": description, "use_sim_time": True}]),
        create,
        Node(package="ros_gz_bridge", executable="parameter_bridge",
             parameters=[{"config_file": os.path.join(share, "config", "bridge.yaml"),
                          "use_sim_time": True}]),
        RegisterEventHandler(OnProcessExit(target_action=create,
                                           on_exit=controllers.spawners(args["with_gripper"]))),
    ]


def mesh_resource_path():
    """The folder gz-sim must search for model://engineer_description (the share folder
    holding the package)."""
    from ament_index_python.packages import get_package_share_directory

    return os.path.dirname(get_package_share_directory("engineer_description"))


def generate_launch_description():
    gz_sim = IncludeLaunchDescription(
        PythonLaunchDescriptionSource(
            PathJoinSubstitution([FindPackageShare("ros_gz_sim"), "launch", "gz_sim.launch.py"])),
        launch_arguments={"gz_args": ["-r ", PathJoinSubstitution(
            [FindPackageShare("engineer_gazebo"), "worlds", LaunchConfiguration("world")])]}.items())
    return LaunchDescription(
        [DeclareLaunchArgument(name, default_value=value) for name, value in ARGS.items()]
        + [AppendEnvironmentVariable("GZ_SIM_RESOURCE_PATH", mesh_resource_path()),
           gz_sim, OpaqueFunction(function=_setup)])
