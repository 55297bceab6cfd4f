"""ROS 2 / Gazebo wiring rules (R1xx): `<ros2_control>`, the controllers YAML, gz-sim
systems and sensors, and the launch files and resource paths a simulation starts with.

R101, R102, R104 and R105 read the description alone (`needs={"document"}`); the others also
read the files beside it (`needs={"package"}`: launch files through Python's `ast`, never
run; YAML; worlds; hooks), which the lint driver collects (`linting.package_reader`).
"""

from __future__ import annotations

import difflib
from collections.abc import Iterator
from dataclasses import dataclass

from robotdesc.diagnostics import Finding, Severity
from robotdesc.model.elements import Collision, MeshRef, Robot, Visual
from robotdesc.rules.package_files import (
    CMAKE,
    HOOK,
    LAUNCH_PY,
    LAUNCH_XML,
    MANIFEST,
    YAML,
    PackageFile,
)
from robotdesc.rules.registry import RuleContext, rule
from robotdesc.rules.ros2_sources import (
    GZ_RESOURCE_VARIABLES,
    controllers,
    elements,
    gazebo_plugins,
    is_classic_filename,
    is_gz_class,
    is_gz_filename,
    launch_nodes,
    loads_gz_systems,
    mentions,
    system_of,
    uses_harmonic,
    world_systems,
)
from robotdesc.source import Provenance, Span

FAMILY = "ros2"

#: The interfaces ros2_control's simulators and controllers know.
STANDARD_INTERFACES = ("position", "velocity", "effort", "acceleration")
#: Joint types a `<ros2_control>` joint cannot be (no single coordinate to command or read).
_NO_INTERFACE_TYPES = frozenset({"fixed", "floating", "planar"})


@rule("R101", "ros2-control-unknown-joint", family=FAMILY, severity=Severity.ERROR,
      needs=("document",))
def ros2_control_unknown_joint(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a `<joint>` in `<ros2_control>` that names no joint of the robot.

    Why is this bad?
    The resource manager refuses the hardware component (gz_ros2_control: "joint not found
    in the model"; mock_components starts, but controllers then claim interfaces that move
    nothing). Usually a joint renamed without its `<ros2_control>` entry, or a prefix the
    macro did not apply.

    Example
    ```xml
    <ros2_control name="Sim" type="system">
      <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
      <joint name="left_wheel"><command_interface name="velocity"/></joint>
    </ros2_control>
    <!-- the robot's joint is left_wheel_joint -->
    ```

    Use instead:
    ```xml
    <joint name="left_wheel_joint"><command_interface name="velocity"/></joint>
    ```
    """
    if ctx.document is None:
        return
    names = {joint.name for joint in robot.joints}
    for item in elements(ctx.document, "/robot/ros2_control/joint"):
        name = item.node.get("name", "")
        if name and name not in names:
            close = difflib.get_close_matches(name, sorted(names), n=1, cutoff=0.8)
            hint = f"; did you mean '{close[0]}'?" if close else ""
            yield Finding(f"<ros2_control> joint '{name}' is not a joint of the robot{hint}",
                          item.where, f"ros2_control:{name}")


@rule("R102", "ros2-control-interface-mismatch", family=FAMILY, severity=Severity.ERROR,
      needs=("document",))
def ros2_control_interface_mismatch(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a `<ros2_control>` joint whose interfaces cannot fit the URDF joint: a fixed,
    floating or planar joint given interfaces, or an interface name that is a misspelt
    standard one (`Position`, `velocty`).

    Custom interface names (real hardware's `current`, `pwm`, ...) are not reported; only
    names within a letter or two of position, velocity, effort or acceleration are.

    Why is this bad?
    Simulators export interfaces only for the joint's single coordinate under the standard
    names: gz_ros2_control skips a fixed joint, and a controller asking for `Position`
    fails to claim it ("not all requested command interfaces exist").

    Example
    ```xml
    <joint name="shoulder"><command_interface name="postion"/></joint>
    ```

    Use instead:
    ```xml
    <joint name="shoulder"><command_interface name="position"/></joint>
    ```
    """
    if ctx.document is None:
        return
    types = {joint.name: joint.type for joint in robot.joints}
    for item in elements(ctx.document, "/robot/ros2_control/joint"):
        name = item.node.get("name", "")
        kind = types.get(name)
        interfaces = [child.get("name", "") for child in item.node
                      if child.tag in ("command_interface", "state_interface")]
        if kind in _NO_INTERFACE_TYPES and interfaces:
            yield Finding(f"<ros2_control> joint '{name}' is {kind} in the URDF: it has no "
                          f"coordinate for the interfaces {', '.join(interfaces)}",
                          item.where, f"ros2_control:{name}")
            continue
        for interface in interfaces:
            if interface in STANDARD_INTERFACES:
                continue
            close = difflib.get_close_matches(interface.lower(), STANDARD_INTERFACES, n=1,
                                              cutoff=0.8)
            if close:
                yield Finding(f"<ros2_control> joint '{name}': interface '{interface}' is "
                              f"not a standard name; did you mean '{close[0]}'?",
                              item.where, f"ros2_control:{name}/{interface}")


@rule("R103", "controller-unknown-joint", family=FAMILY, severity=Severity.ERROR,
      needs=("package",))
def controller_unknown_joint(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a controller in the controllers YAML the description names (`<parameters>` of
    a gz_ros2_control / gazebo_ros2_control plugin) that names joints the robot lacks, while
    naming some it has.

    A controller that names none of the robot's joints is taken to be for another variant
    and is not judged (a gripper's controller in a file shared by robots with and without
    the gripper). YAML files the description does not name: R110 (opt-in).

    Why is this bad?
    The controller manager loads the controller but cannot activate it: "not all requested
    interfaces exist" for a diff drive or trajectory controller, and the joint never moves.
    Typical: a wheel count or prefix changed in the xacro, not in the YAML.

    Example
    ```yaml
    arm_controller:
      ros__parameters:
        joints: [waist, shoulder, elbw]
    ```

    Use instead:
    ```yaml
    arm_controller:
      ros__parameters:
        joints: [waist, shoulder, elbow]
    ```
    """
    if ctx.package is None:
        return
    yield from _unknown_controller_joints(robot, ctx.package.named)


@rule("R110", "package-controller-unknown-joint", family=FAMILY, severity=Severity.WARNING,
      needs=("package",), opt_in=True)
def package_controller_unknown_joint(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a controller in a YAML file of the description's own package that names joints
    the robot lacks, while naming some it has (R103 judges the file the description names).

    Opt-in: a package often holds the controllers of several variants (a 7-joint arm's file
    beside the 6-joint arm's), and the file a launch file passes cannot be told from the
    package alone.

    Why is this bad?
    When the file is the one a launch file passes, the controller cannot be activated (see
    R103).

    Example
    ```yaml
    arm_controller:
      ros__parameters:
        joints: [shoulder, elbow, wrist_3]
    ```

    Use instead (for a robot whose last joint is `wrist`):
    ```yaml
    arm_controller:
      ros__parameters:
        joints: [shoulder, elbow, wrist]
    ```
    """
    if ctx.package is None or not ctx.package.packages:
        return
    named = {f.path for f in ctx.package.named}
    own = tuple(f for f in ctx.package.packages[0].of_kind(YAML) if f.path not in named)
    yield from _unknown_controller_joints(robot, own)


def _unknown_controller_joints(robot: Robot,
                               files: tuple[PackageFile, ...]) -> Iterator[Finding]:
    names = {joint.name for joint in robot.joints}
    for file in files:
        for controller in controllers(file):
            joints = controller.joints
            if not any(joint in names for joint, _ in joints):
                continue
            missing = [(joint, line) for joint, line in joints if joint not in names]
            if missing:
                shown = ", ".join(f"'{j}'" for j, _ in missing[:5])
                more = f" and {len(missing) - 5} more" if len(missing) > 5 else ""
                yield Finding(f"controller '{controller.name}' names {shown}{more}, not "
                              f"joints of the robot", Provenance(Span(file.path,
                                                                      missing[0][1])),
                              f"controller:{controller.name}")


@rule("R104", "gazebo-plugin-simulator-mismatch", family=FAMILY, severity=Severity.ERROR,
      needs=("document",))
def gazebo_plugin_simulator_mismatch(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a `<plugin>` that names a gz-sim system class with a Gazebo Classic library
    (`libgazebo_ros_*.so`), or a gz-sim system library (`gz-sim-*-system`) with a name that
    is not a system class.

    Why is this bad?
    gz-sim loads a system by library and class: a Classic library is not found ("Failed to
    load system plugin"), and a name like `imu_plugin` is no class in `gz-sim-imu-system`,
    so the system never runs. Gazebo Classic, for its part, cannot open a gz-sim library.

    Example
    ```xml
    <gazebo>
      <plugin filename="libgazebo_ros2_control.so" name="gz_ros2_control::GazeboSimROS2ControlPlugin"/>
      <plugin filename="gz-sim-imu-system" name="imu_plugin"/>
    </gazebo>
    ```

    Use instead:
    ```xml
    <gazebo>
      <plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin"/>
      <plugin filename="gz-sim-imu-system" name="gz::sim::systems::Imu"/>
    </gazebo>
    ```
    """
    if ctx.document is None:
        return
    for item in gazebo_plugins(ctx.document):
        filename = item.node.get("filename", "")
        name = item.node.get("name", "")
        if is_gz_class(name) and is_classic_filename(filename):
            yield Finding(f"plugin '{name}' is a gz-sim system, but '{filename}' is a Gazebo "
                          "Classic library", item.where, f"plugin:{name}")
        elif is_gz_filename(filename) and name and "::" not in name:
            yield Finding(f"plugin '{filename}' is a gz-sim system library, but '{name}' is "
                          "not a system class (gz::sim::systems::...)", item.where,
                          f"plugin:{filename}")


@rule("R105", "gz-ray-sensor", family=FAMILY, severity=Severity.ERROR, needs=("document",))
def gz_ray_sensor(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a `<sensor type="ray">` in a description that loads gz-sim systems.

    Why is this bad?
    `ray` is Gazebo Classic's CPU laser. gz-sim's Sensors system creates rendering sensors
    only, so the laser is never made: no scan topic, no error. gz-sim's laser is
    `gpu_lidar` (same `<ray>` block, called `<lidar>` in SDF 1.6+, both accepted).

    Example
    ```xml
    <gazebo reference="laser_link">
      <sensor type="ray" name="laser"><topic>scan</topic></sensor>
    </gazebo>
    <gazebo><plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin"/></gazebo>
    ```

    Use instead:
    ```xml
    <sensor type="gpu_lidar" name="laser"><topic>scan</topic></sensor>
    ```
    """
    if ctx.document is None or not loads_gz_systems(ctx.document):
        return
    for item in elements(ctx.document, "/robot/gazebo/sensor[@type='ray']"):
        name = item.node.get("name", "")
        yield Finding(f"sensor '{name}' is type 'ray' (Gazebo Classic's CPU laser), but the "
                      "description loads gz-sim systems, whose Sensors system makes no ray "
                      "sensor: use type 'gpu_lidar'", item.where, f"sensor:{name}")


@rule("R106", "gz-world-system-per-model", family=FAMILY, severity=Severity.WARNING,
      needs=("document", "package"))
def gz_world_system_per_model(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a world-wide gz-sim system (Imu, Sensors, Contact, Magnetometer, ...) loaded by
    the robot while a world file of its packages loads it too.

    Why is this bad?
    These systems serve every sensor of the world. Loaded twice, each instance updates the
    same sensors: the IMU publishes every message twice, the Sensors system renders twice.
    Load them once, in the world.

    Example
    ```xml
    <gazebo><plugin filename="gz-sim-imu-system" name="gz::sim::systems::Imu"/></gazebo>
    <!-- worlds/empty.sdf loads gz::sim::systems::Imu as well -->
    ```

    Use instead (the world file keeps its `<plugin filename="gz-sim-imu-system" ...>`):
    ```xml
    <gazebo><plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin"/></gazebo>
    ```
    """
    if ctx.document is None or ctx.package is None:
        return
    worlds = [(f, world_systems(f)) for f in ctx.package.files("world")]
    for item in elements(ctx.document, "/robot/gazebo[not(@reference)]/plugin"):
        system = system_of(item.node.get("filename", ""), item.node.get("name", ""))
        if system is None:
            continue
        loading = [_shown(f.path, ctx) for f, systems in worlds if system in systems]
        if loading:
            yield Finding(f"the world-wide system {system} is loaded by the robot and by the "
                          f"world {loading[0]}: every {system.lower()} message comes twice",
                          item.where, f"plugin:{system}")


@rule("R107", "gz-resource-path-not-exported", family=FAMILY, severity=Severity.WARNING,
      needs=("document", "package"), opt_in=True)
def gz_resource_path_not_exported(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds `package://` meshes in a description that loads gz-sim systems, when nothing
    tells gz-sim where the package is: no environment hook setting `GZ_SIM_RESOURCE_PATH`
    (or `IGN_GAZEBO_RESOURCE_PATH`), no `<gazebo_ros gazebo_model_path=...>` export in its
    package.xml, and no launch file of the packages setting the variable
    (`AppendEnvironmentVariable`, `SetEnvironmentVariable`).

    Reported once per mesh package, at its first mesh. Packages robotdesc did not read are
    not judged. Opt-in: the variable is often set by a bringup package the description does
    not use (so robotdesc does not read it) or in the user's shell.

    Why is this bad?
    gz-sim turns `package://pkg/meshes/x.stl` into `model://pkg/meshes/x.stl` and searches
    `GZ_SIM_RESOURCE_PATH` for `pkg`: without it every mesh is "Unable to find file" and
    the robot is invisible, with no collision meshes.

    Example
    A launch file:
    ```python
    return LaunchDescription([gz_sim, spawn])
    ```

    Use instead:
    ```python
    share = os.path.dirname(get_package_share_directory("my_description"))
    return LaunchDescription([AppendEnvironmentVariable("GZ_SIM_RESOURCE_PATH", share),
                              gz_sim, spawn])
    ```
    """
    if ctx.document is None or ctx.package is None or not loads_gz_systems(ctx.document):
        return
    launch_sets = any(mentions(f, GZ_RESOURCE_VARIABLES)
                      for f in ctx.package.files(LAUNCH_PY, LAUNCH_XML))
    if launch_sets:
        return
    reported: set[str] = set()
    for link in robot.links:
        parts: list[Visual | Collision] = [*link.visuals, *link.collisions]
        for part in parts:
            mesh = part.geometry
            if not isinstance(mesh, MeshRef) or not mesh.filename.startswith("package://"):
                continue
            filename = mesh.filename
            name = filename[len("package://"):].split("/", 1)[0]
            package = ctx.package.package(name)
            if name in reported or package is None:
                continue
            reported.add(name)
            if _exports_resource_path(package.of_kind(HOOK, CMAKE, MANIFEST)):
                continue
            yield Finding(f"'{filename}': gz-sim finds package '{name}' only through "
                          "GZ_SIM_RESOURCE_PATH, and no hook, package.xml export or launch "
                          "file of the packages sets it", mesh.where or part.where or link.where,
                          f"package:{name}")


def _shown(path: str, ctx: RuleContext) -> str:
    """A file of the packages as `package/relative/path`."""
    for package in ctx.package.packages if ctx.package else ():
        if path.startswith(package.path + "/"):
            return f"{package.name}/{path[len(package.path) + 1:]}"
    return path


def _exports_resource_path(files: tuple[PackageFile, ...]) -> bool:
    """Whether a package's hooks, CMakeLists.txt or package.xml export a gz resource path."""
    for file in files:
        text = file.text
        if file.kind == MANIFEST:
            if "gazebo_model_path" in text or "gazebo_media_path" in text:
                return True
        elif any(variable in text for variable in GZ_RESOURCE_VARIABLES):
            return True
    return False


@dataclass(frozen=True)
class RemovedParameterOptions:
    """Options of R108.

    Attributes:
        distro: the ROS 2 distribution the package targets ("jazzy", "kilted", "rolling",
            "humble", ...); "" infers Jazzy from gz-sim Harmonic names in the description
            (`gz-sim-*` systems, `gz_ros2_control-system`, `<gz_frame_id>`).
    """

    distro: str = ""


#: diff_drive_controller parameters Jazzy no longer reads (ros2_controllers' Jazzy migration
#: notes: stamped `cmd_vel` always; limits disabled by NaN instead of the flags).
REMOVED_IN_JAZZY = {
    "use_stamped_vel": "Jazzy always subscribes to geometry_msgs/TwistStamped on ~/cmd_vel",
    "has_velocity_limits": "set the limits to .NAN to disable them",
    "has_acceleration_limits": "set the limits to .NAN to disable them",
    "has_jerk_limits": "set the limits to .NAN to disable them",
    "wheels_per_side": "removed (unused)",
}
_JAZZY_OR_LATER = frozenset({"jazzy", "kilted", "lyrical", "rolling"})


@rule("R108", "jazzy-removed-controller-parameter", family=FAMILY, severity=Severity.WARNING,
      options=RemovedParameterOptions, needs=("document", "package"))
def jazzy_removed_controller_parameter(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds diff_drive_controller parameters that ROS 2 Jazzy no longer reads
    (`use_stamped_vel`, `has_velocity_limits`, `has_acceleration_limits`,
    `has_jerk_limits`, `wheels_per_side`) in a ROS 2 controllers YAML of a package that
    targets Jazzy or later.

    The distribution is the option `distro`; by default Jazzy is assumed when the
    description uses gz-sim Harmonic's names (Harmonic is Jazzy's Gazebo). Judged: the
    YAML the description names and the YAML files of its packages.

    Why is this bad?
    The parameters are ignored without a word. `use_stamped_vel: false` does not make the
    controller take `Twist`: it takes `TwistStamped` only, and a teleop publishing `Twist`
    moves nothing. `has_*_limits: false` no longer switches a limit off.

    Example
    ```yaml
    base_controller:
      ros__parameters:
        left_wheel_names: [left_wheel]
        right_wheel_names: [right_wheel]
        use_stamped_vel: false
        linear.x.has_velocity_limits: true
        linear.x.max_velocity: 1.0
    ```

    Use instead:
    ```yaml
    base_controller:
      ros__parameters:
        left_wheel_names: [left_wheel]
        right_wheel_names: [right_wheel]
        linear.x.max_velocity: 1.0
    ```
    """
    if ctx.package is None or ctx.document is None:
        return
    distro = ctx.options_as(RemovedParameterOptions).distro.strip().lower()
    if distro:
        if distro not in _JAZZY_OR_LATER:
            return
    elif not uses_harmonic(ctx.document):
        return
    for file in ctx.package.files(YAML):
        for controller in controllers(file):
            if not controller.ros2 or not any(
                    key in ("left_wheel_names", "right_wheel_names")
                    for key, _ in controller.keys):
                continue
            for key, line in controller.keys:
                last = key.rsplit(".", 1)[-1]
                if last in REMOVED_IN_JAZZY:
                    yield Finding(f"controller '{controller.name}': '{key}' is not read by "
                                  f"Jazzy's diff_drive_controller ({REMOVED_IN_JAZZY[last]})",
                                  Provenance(Span(file.path, line)),
                                  f"controller:{controller.name}/{key}")


@rule("R109", "remap-on-spawner", family=FAMILY, severity=Severity.ERROR, needs=("package",))
def remap_on_spawner(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds remappings given to a controller_manager `spawner` node in a launch file
    (Python launch files read with `ast`, XML launch files as XML).

    Why is this bad?
    The spawner only calls the controller manager's services and exits; remapping its
    topics changes nothing. The controller keeps listening on `/<controller>/cmd_vel`, so
    a `/cmd_vel` remapped on the spawner moves nothing. Remap on the controller manager
    node (`ros2_control_node`, or the simulator plugin's `<ros><remapping>`), or relay the
    topic.

    Example
    ```python
    Node(package="controller_manager", executable="spawner", arguments=["base_controller"],
         remappings=[("/base_controller/cmd_vel", "/cmd_vel")])
    ```

    Use instead:
    ```python
    Node(package="controller_manager", executable="ros2_control_node",
         remappings=[("/base_controller/cmd_vel", "/cmd_vel")])
    ```
    """
    if ctx.package is None:
        return
    for file in ctx.package.files(LAUNCH_PY, LAUNCH_XML):
        for node in launch_nodes(file):
            if node.remapped and node.package == "controller_manager" \
                    and node.executable.startswith("spawner"):
                yield Finding("remappings on a controller_manager spawner change nothing: the "
                              "spawner only loads and activates controllers; remap on the "
                              "controller manager or relay the topic",
                              Provenance(Span(file.path, node.line)), f"launch:{node.line}")
