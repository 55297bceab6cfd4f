"""ROS 2: show the Engineer in RViz 2 with sliders for its joints.

ros2 launch engineer_description display.launch.py [main_track_wheels:=56] [with_gripper:=true]
"""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue
from launch_ros.substitutions import FindPackageShare

ARGS = {"main_track_wheels": "56", "flipper_track_wheels": "50", "with_gripper": "true",
        "show_wheels": "false"}


def generate_launch_description() -> LaunchDescription:
    share = FindPackageShare("engineer_description")
    xacro_args = []
    for name in ARGS:
        xacro_args += [" ", f"{name}:=", LaunchConfiguration(name)]
    description = Command(["xacro ", PathJoinSubstitution([share, "urdf", "engineer.urdf.xacro"]),
                           *xacro_args])
    return LaunchDescription(
        [DeclareLaunchArgument(name, default_value=value) for name, value in ARGS.items()]
        + [
            Node(package="robot_state_publisher", executable="robot_state_publisher",
                 parameters=[{"robot_description": ParameterValue(description, value_type=str)}]),
            Node(package="joint_state_publisher_gui", executable="joint_state_publisher_gui"),
            Node(package="rviz2", executable="rviz2", arguments=["-f", "base_footprint"]),
        ])
