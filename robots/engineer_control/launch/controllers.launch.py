"""ROS 2: start the Engineer's controllers in a running controller manager (gz_ros2_control's).

ros2 launch engineer_control controllers.launch.py [main_track_wheels:=56] [flipper_track_wheels:=50]

The controllers file for the wheel counts is written by `controllers_file_for` (the same
generator as scripts/make_controllers.py); gz_ros2_control reads it through the model's
xacro argument controllers_file (engineer_gazebo's gz.launch.py passes both).

Both diff drives follow /cmd_vel (geometry_msgs/TwistStamped, ROS 2 Jazzy) through the
remappings of the controller manager that loads them (engineer_gazebo's model gives them to
gz_ros2_control). The spawner gets none: it only asks the controller manager to load and
activate the controllers, so remapping its topics would change nothing.
"""

import os
import sys
import tempfile

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch_ros.actions import Node

SCRIPTS = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts")
CONTROLLERS = ("joint_state_broadcaster", "mobile_base_controller", "flipper_tracks_controller",
               "arm_controller", "flippers_controller", "gripper_controller")
ARGS = {"main_track_wheels": "56", "flipper_track_wheels": "50", "with_gripper": "true"}


def controllers_file_for(main_track_wheels, flipper_track_wheels):
    """Write the ROS 2 controllers YAML for these wheel counts; its path."""
    sys.path.insert(0, SCRIPTS)
    try:
        import make_controllers
    finally:
        sys.path.remove(SCRIPTS)
    text = make_controllers.ros2_yaml(int(main_track_wheels), int(flipper_track_wheels))
    handle, path = tempfile.mkstemp(prefix="engineer_controllers_", suffix=".yaml")
    with os.fdopen(handle, "w", encoding="utf-8") as stream:
        stream.write(text)
    return path


#: How long the spawner waits for the controller manager (s): gz_ros2_control starts it only
#: once gz-sim has the model, which takes long for 212 wheels.
MANAGER_TIMEOUT = "120"


def controller_names(with_gripper="true"):
    """The controllers to start (the gripper's only with a gripper)."""
    return [c for c in CONTROLLERS if with_gripper == "true" or c != "gripper_controller"]


def spawners(with_gripper="true"):
    """One controller_manager spawner that loads and activates every controller in turn."""
    return [Node(package="controller_manager", executable="spawner",
                 arguments=[*controller_names(with_gripper),
                            "--controller-manager-timeout", MANAGER_TIMEOUT],
                 output="screen")]


def generate_launch_description():
    return LaunchDescription(
        [DeclareLaunchArgument(name, default_value=value) for name, value in ARGS.items()]
        + spawners())
