"""What the R1xx rules read in a description's `<ros2_control>` and `<gazebo>` elements and
in the files beside it (`rules.package_files`): launch nodes (Python launch files through
`ast`, never run; XML launch files through lxml), controller YAML with line numbers, the
systems a world loads. Pure functions of text, cached by their arguments.
"""

from __future__ import annotations

import ast
import functools
import re
from collections.abc import Iterator
from dataclasses import dataclass

import yaml
from lxml import etree

from robotdesc.rules.package_files import LAUNCH_PY, PackageFile
from robotdesc.rules.registry import SourceDocument
from robotdesc.source import PROVENANCE_ATTR, Provenance, Span, decode_provenance
from robotdesc.xml_input import shared_root

# --- gz-sim and Gazebo Classic plugin names -------------------------------------------------

_GZ_FILENAME = re.compile(r"^(lib)?(gz-sim|ignition-gazebo|gz_ros2_control-system|"
                          r"ign_ros2_control-system)")
_GZ_CLASS = re.compile(r"^(gz::sim::|ignition::gazebo::|gz_ros2_control::|ign_ros2_control::)")
_CLASSIC_FILENAME = re.compile(r"^lib\w*\.so$")
#: gz-sim systems that serve the whole world: loaded once, in the world file.
WORLD_SYSTEMS = frozenset({"Imu", "Sensors", "Contact", "Magnetometer", "AirPressure",
                           "Altimeter", "NavSat", "ForceTorque"})
#: Environment variables gz-sim searches for `model://` (what `package://` becomes).
GZ_RESOURCE_VARIABLES = ("GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH")


def is_gz_filename(filename: str) -> bool:
    """A gz-sim (or Ignition Gazebo) system library name: `gz-sim-imu-system`, ..."""
    return bool(_GZ_FILENAME.match(filename))


def is_gz_class(name: str) -> bool:
    """A gz-sim system's class name: `gz::sim::systems::Imu`, ..."""
    return bool(_GZ_CLASS.match(name))


def is_classic_filename(filename: str) -> bool:
    """A Gazebo Classic plugin library: `libgazebo_ros_imu_sensor.so`, ..."""
    return bool(_CLASSIC_FILENAME.match(filename)) and not is_gz_filename(filename)


def system_of(filename: str, name: str) -> str | None:
    """The world-wide system a gz plugin loads (`Imu`, `Sensors`, ...), or None."""
    if is_gz_class(name):
        short = name.rsplit("::", 1)[-1]
        return short if short in WORLD_SYSTEMS else None
    match = re.match(r"^(?:lib)?(?:gz-sim|ignition-gazebo)\d*-([a-z-]+)-system", filename)
    if match:
        short = "".join(part.capitalize() for part in match.group(1).split("-"))
        short = {"Navsat": "NavSat", "Forcetorque": "ForceTorque"}.get(short, short)
        return short if short in WORLD_SYSTEMS else None
    return None


# --- the description's elements -------------------------------------------------------------


@dataclass(frozen=True)
class Element:
    """An element of the expanded description with where it was written."""

    node: etree._Element
    where: Provenance


def _parse(xml: bytes) -> etree._Element | None:
    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                             remove_comments=True, remove_pis=True)
    try:
        return etree.fromstring(xml, parser)
    except (etree.XMLSyntaxError, ValueError):
        return None


def _where(document: SourceDocument, node: etree._Element) -> Provenance:
    value = node.get(PROVENANCE_ATTR) if document.files else None
    if value is not None:
        try:
            return decode_provenance(value, tuple(document.files))
        except (ValueError, IndexError):
            pass
    return Provenance(Span(document.path, node.sourceline or 0))


def elements(document: SourceDocument, path: str) -> Iterator[Element]:
    """Elements at an XPath of the document (`//ros2_control/joint`), with provenance."""
    root = shared_root(document.xml)
    if root is None:
        return
    for node in root.xpath(path):
        if isinstance(node, etree._Element):
            yield Element(node, _where(document, node))


def gazebo_plugins(document: SourceDocument) -> list[Element]:
    """Every `<plugin>` inside a `<gazebo>` element (robot-wide, per link, or in a sensor)."""
    return list(elements(document, "/robot/gazebo//plugin"))


def loads_gz_systems(document: SourceDocument) -> bool:
    """Whether the description loads gz-sim systems (it is meant for gz-sim)."""
    return any(is_gz_filename(e.node.get("filename", "")) for e in gazebo_plugins(document))


def uses_harmonic(document: SourceDocument) -> bool:
    """Whether the description uses names gz-sim Harmonic brought (the pairing of ROS 2
    Jazzy): `gz-sim-*` systems, `gz_ros2_control-system`, `<gz_frame_id>`."""
    filenames = [e.node.get("filename", "") for e in gazebo_plugins(document)]
    return (any(f.startswith(("gz-sim", "libgz-sim", "gz_ros2_control")) for f in filenames)
            or any(True for _ in elements(document, "/robot/gazebo//gz_frame_id")))


# --- launch files ---------------------------------------------------------------------------


@dataclass(frozen=True)
class LaunchNode:
    """A node a launch file starts (as far as the text says).

    Attributes:
        package, executable: the literal values, "" when not a literal.
        remapped: whether remappings are given (`remappings=` or `<remap>`).
        line: where the node is written.
    """

    package: str
    executable: str
    remapped: bool
    line: int


def launch_nodes(file: PackageFile) -> tuple[LaunchNode, ...]:
    """The nodes of a launch file, read statically."""
    if file.kind == LAUNCH_PY:
        return _python_nodes(file.text)
    return _xml_nodes(file.text)


@functools.lru_cache(maxsize=64)
def _python_nodes(text: str) -> tuple[LaunchNode, ...]:
    try:
        tree = ast.parse(text)
    except (SyntaxError, ValueError):
        return ()
    nodes = []
    for call in ast.walk(tree):
        if not isinstance(call, ast.Call):
            continue
        function = call.func
        called = function.id if isinstance(function, ast.Name) else (
            function.attr if isinstance(function, ast.Attribute) else "")
        if called != "Node":
            continue
        keywords = {k.arg: k.value for k in call.keywords if k.arg}
        remappings = keywords.get("remappings")
        remapped = remappings is not None and not (
            isinstance(remappings, (ast.List, ast.Tuple)) and not remappings.elts) and not (
            isinstance(remappings, ast.Constant) and remappings.value is None)
        nodes.append(LaunchNode(_literal(keywords.get("package")),
                                _literal(keywords.get("executable", keywords.get("node_executable"))),
                                remapped, call.lineno))
    return tuple(nodes)


def _literal(node: ast.expr | None) -> str:
    return node.value if isinstance(node, ast.Constant) and isinstance(node.value, str) else ""


@functools.lru_cache(maxsize=64)
def _xml_nodes(text: str) -> tuple[LaunchNode, ...]:
    root = _parse(text.encode("utf-8"))
    if root is None:
        return ()
    return tuple(LaunchNode(node.get("pkg", ""), node.get("type", node.get("exec", "")),
                            any(child.tag == "remap" for child in node), node.sourceline or 0)
                 for node in root.iter("node"))


def mentions(file: PackageFile, words: tuple[str, ...]) -> bool:
    """Whether the file names one of `words`: in a Python launch file as a string (not in a
    comment), elsewhere anywhere in the text."""
    if file.kind != LAUNCH_PY:
        return any(word in file.text for word in words)
    return any(word in string for string in _python_strings(file.text) for word in words)


@functools.lru_cache(maxsize=64)
def _python_strings(text: str) -> tuple[str, ...]:
    try:
        tree = ast.parse(text)
    except (SyntaxError, ValueError):
        return ()
    return tuple(node.value for node in ast.walk(tree)
                 if isinstance(node, ast.Constant) and isinstance(node.value, str))


# --- controller YAML ------------------------------------------------------------------------

#: Keys whose values are joint names in ros2_controllers' and ros_control's controllers.
JOINT_KEYS = frozenset({"joints", "joint", "joint_name", "left_wheel_names",
                        "right_wheel_names", "left_wheel", "right_wheel",
                        "front_wheels_names", "rear_wheels_names"})


@dataclass(frozen=True)
class ControllerEntry:
    """A controller's settings in a YAML file.

    Attributes:
        name: the controller's name (the key above its settings; `ros__parameters` skipped).
        joints: (joint name, line) of every joint it names.
        keys: (parameter name with dots for nesting, line) of every parameter.
        ros2: whether its settings sit under `ros__parameters`.
    """

    name: str
    joints: tuple[tuple[str, int], ...]
    keys: tuple[tuple[str, int], ...]
    ros2: bool


def controllers(file: PackageFile) -> tuple[ControllerEntry, ...]:
    """The controllers configured in a YAML file (none when it is not YAML)."""
    return _controllers(file.text)


@functools.lru_cache(maxsize=64)
def _controllers(text: str) -> tuple[ControllerEntry, ...]:
    try:
        documents = list(yaml.compose_all(text, Loader=yaml.SafeLoader))
    except yaml.YAMLError:
        return ()
    found: list[ControllerEntry] = []
    for document in documents:
        if document is not None:
            _collect(document, "", False, found)
    return tuple(found)


def _collect(node: yaml.Node, name: str, ros2: bool, found: list[ControllerEntry]) -> None:
    if not isinstance(node, yaml.MappingNode):
        return
    keys = {key.value: value for key, value in node.value if isinstance(key, yaml.ScalarNode)}
    if any(k in JOINT_KEYS for k in keys) or "type" in keys and name:
        joints = []
        for key in sorted(JOINT_KEYS & set(keys)):
            joints.extend(_names(keys[key]))
        found.append(ControllerEntry(name, tuple(joints), tuple(_flat(node, "")), ros2))
        return
    for key, value in node.value:
        if isinstance(key, yaml.ScalarNode):
            inner_ros2 = key.value == "ros__parameters"
            _collect(value, name if inner_ros2 else str(key.value), inner_ros2 or ros2, found)


def _names(node: yaml.Node) -> list[tuple[str, int]]:
    if isinstance(node, yaml.ScalarNode) and node.value:
        return [(str(node.value), node.start_mark.line + 1)]
    if isinstance(node, yaml.SequenceNode):
        return [(str(item.value), item.start_mark.line + 1) for item in node.value
                if isinstance(item, yaml.ScalarNode) and item.value]
    return []


def _flat(node: yaml.Node, prefix: str) -> Iterator[tuple[str, int]]:
    if not isinstance(node, yaml.MappingNode):
        return
    for key, value in node.value:
        if not isinstance(key, yaml.ScalarNode):
            continue
        name = f"{prefix}{key.value}"
        yield name, key.start_mark.line + 1
        yield from _flat(value, name + ".")


# --- worlds ---------------------------------------------------------------------------------


def world_systems(file: PackageFile) -> dict[str, int]:
    """The world-wide systems a world file loads at world level: name -> line."""
    return dict(_world_systems(file.text))


@functools.lru_cache(maxsize=32)
def _world_systems(text: str) -> tuple[tuple[str, int], ...]:
    root = _parse(text.encode("utf-8"))
    if root is None:
        return ()
    found = []
    for world in root.iter("world"):
        for plugin in world.findall("plugin"):
            system = system_of(plugin.get("filename", ""), plugin.get("name", ""))
            if system:
                found.append((system, plugin.sourceline or 0))
    return tuple(found)
