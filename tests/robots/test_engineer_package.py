"""The Engineer description package (robots/engineer_description): files, meshes, expansion."""

from __future__ import annotations

import importlib
import re
import struct
import sys
from pathlib import Path

import numpy as np
import pytest
from lxml import etree

PACKAGE = Path(__file__).resolve().parents[2] / "robots" / "engineer_description"
TOP = PACKAGE / "urdf" / "engineer.urdf.xacro"
MESH_DIR = PACKAGE / "meshes" / "visual"
TABLE_I_MASS = 16.3  # kg, Table I of the second paper
GRIPPER_MASS = 0.05 + 2 * (0.04 + 0.03 + 0.03)  # kg, urdf/properties.xacro (base + two sides)


# ----------------------------------------------------------------------------- helpers

@pytest.fixture(scope="module")
def scripts():
    """The package's scripts as modules (they import each other by plain name)."""
    sys.path.insert(0, str(PACKAGE / "scripts"))
    try:
        yield importlib.import_module("package_properties")
    finally:
        sys.path.remove(str(PACKAGE / "scripts"))


def _expanded(**args: str):
    from robotdesc.expansion import ExpandOptions, expand_file

    options = ExpandOptions(use_cache=False)
    return expand_file(TOP, {k: str(v) for k, v in args.items()}, options=options)


def _expand(**args: str) -> etree._Element:
    return etree.fromstring(_expanded(**args).xml)


@pytest.fixture(scope="module")
def default_expansion():
    return _expanded()


@pytest.fixture(scope="module")
def robot(default_expansion) -> etree._Element:
    return etree.fromstring(default_expansion.xml)


def _joints(root, kind=None):
    return [j for j in root.findall("joint") if kind is None or j.get("type") == kind]


def _total_mass(root) -> float:
    return sum(float(m.get("value")) for m in root.findall("link/inertial/mass"))


def _stl_triangles(path: Path) -> int:
    with path.open("rb") as handle:
        handle.seek(80)
        return struct.unpack("<I", handle.read(4))[0]


# ----------------------------------------------------------------------------- package files

def test_package_xml_is_format_3_for_catkin_and_ament():
    root = etree.parse(str(PACKAGE / "package.xml")).getroot()
    assert root.get("format") == "3"
    assert root.findtext("name") == "engineer_description"
    tools = {t.get("condition"): t.text for t in root.findall("buildtool_depend")}
    assert tools == {"$ROS_VERSION == 1": "catkin", "$ROS_VERSION == 2": "ament_cmake"}
    assert {"xacro", "urdf"} <= {d.text for d in root.findall("exec_depend")}


def test_cmake_installs_the_share_folders_for_both_build_systems():
    text = (PACKAGE / "CMakeLists.txt").read_text()
    assert "ament_package()" in text and "catkin_package()" in text
    assert text.count("install(DIRECTORY urdf meshes config launch") == 2
    for folder in ("urdf", "meshes", "config", "launch"):
        assert (PACKAGE / folder).is_dir()


CONTROL = PACKAGE.parent / "engineer_control"


def test_track_controllers_yaml_is_current():
    sys.path.insert(0, str(CONTROL / "scripts"))
    try:
        make = importlib.import_module("make_controllers")
    finally:
        sys.path.remove(str(CONTROL / "scripts"))
    assert (CONTROL / "config" / "engineer_tracks.yaml").read_text() == make.ros1_tracks_yaml(56, 50)
    assert (CONTROL / "config" / "engineer_ros2_controllers.yaml").read_text() == make.ros2_yaml(56, 50)


def test_readme_polygon_table_matches_the_meshes():
    readme = (PACKAGE / "README.md").read_text()
    for stl in sorted(MESH_DIR.glob("*.stl")):
        row = re.search(rf"^\| `{stl.name}` \| ([\d,]+) \|", readme, re.MULTILINE)
        assert row, f"no README row for {stl.name}"
        assert int(row.group(1).replace(",", "")) == _stl_triangles(stl), stl.name


def test_readme_polygon_table_lists_every_collision_set(scripts):
    from robotdesc.collision.manifest import read_manifest

    readme = (PACKAGE / "README.md").read_text()
    make = importlib.import_module("make_collision")
    for item in make.SETS:
        manifest = read_manifest(str(PACKAGE / item.folder))
        triangles = sum(_stl_triangles(PACKAGE / item.folder / name)
                        for name in manifest.files if name.endswith(".stl"))
        row = re.search(rf"^\| `{item.folder}/` \| [^|]+ \| ([\d,]+) \|", readme, re.MULTILINE)
        assert row, f"no README row for {item.folder}"
        assert int(row.group(1).replace(",", "")) == triangles, item.folder


# ----------------------------------------------------------------------------- meshes

@pytest.mark.slow
def test_mesh_script_reproduces_committed_meshes(scripts, tmp_path):
    pytest.importorskip("manifold3d", reason="the mesh script needs manifold3d")
    trimesh = pytest.importorskip("trimesh")
    make = importlib.import_module("make_meshes")
    make.build(tmp_path, PACKAGE / "urdf" / "properties.xacro")
    built = sorted(p.name for p in (tmp_path / "meshes" / "visual").glob("*.stl"))
    assert built == sorted(p.name for p in MESH_DIR.glob("*.stl"))
    for name in built:
        new, old = tmp_path / "meshes" / "visual" / name, MESH_DIR / name
        if new.read_bytes() == old.read_bytes():
            continue
        # another manifold3d build may triangulate differently: compare the solids instead
        a, b = trimesh.load(new), trimesh.load(old)
        assert np.allclose(a.bounds, b.bounds, atol=1e-6), name
        assert a.volume == pytest.approx(b.volume, rel=1e-4), name
        assert a.area == pytest.approx(b.area, rel=1e-4), name


def test_inertials_are_robotdesc_measurements_of_the_collision_geometry(scripts):
    make = importlib.import_module("make_inertials")
    numbers = re.compile(r"-?\d+(?:\.\d+)?(?:e-?\d+)?")
    fresh = make.inertials_xacro(make.measure())
    committed = (PACKAGE / "urdf" / "inertials.generated.xacro").read_text()
    assert "collision geometry" in committed
    assert np.allclose([float(v) for v in numbers.findall(fresh)],
                       [float(v) for v in numbers.findall(committed)], rtol=1e-6, atol=1e-12)


@pytest.mark.slow
def test_collision_meshes_match_their_manifests(scripts):
    """`robotdesc collision ... --check` with each set's own command line: nothing stale."""
    from robotdesc.cli import main

    make = importlib.import_module("make_collision")
    assert make.SETS
    for item in make.SETS:
        assert (PACKAGE / item.folder / "robotdesc-collision.json").is_file(), item.folder
        assert main(item.arguments(check=True, jobs=1)) == 0, item.folder


def test_collision_check_notices_an_edited_mesh(scripts, tmp_path):
    """The guard can fail: a copy of a set with one mesh changed is reported stale."""
    import shutil

    from robotdesc.collision.manifest import read_manifest

    make = importlib.import_module("make_collision")
    item = make.SETS[0]
    copy = tmp_path / "set"
    shutil.copytree(PACKAGE / item.folder, copy)
    manifest = read_manifest(str(copy))
    first = sorted(name for name in manifest.files if name.endswith(".stl"))[0]
    with open(copy / first, "ab") as stream:
        stream.write(b"\0")
    from robotdesc.cli import main

    args = item.arguments(check=True, jobs=1)
    args[args.index("--out") + 1] = str(copy)
    assert main(args) == 1


def test_meshes_fit_the_size_budget():
    total = sum(p.stat().st_size for p in PACKAGE.rglob("*") if p.is_file())
    assert total < 30 * 1024 * 1024


# ----------------------------------------------------------------------------- expanded model

def test_default_model_has_212_wheels_and_table_i_mass(robot):
    wheels = _joints(robot, "continuous")
    assert len(wheels) == 212
    assert sum(j.get("name").startswith("left_main_wheel_") for j in wheels) == 56
    assert sum(j.get("name").startswith("right_flipper_wheel_") for j in wheels) == 50
    assert _total_mass(robot) == pytest.approx(TABLE_I_MASS, abs=1e-9)
    assert robot.find("link[@name='base_footprint']/inertial") is None


def test_wheel_counts_follow_the_xacro_arguments():
    root = _expand(main_track_wheels=8, flipper_track_wheels=3)
    assert len(_joints(root, "continuous")) == 2 * 8 + 2 * 3
    assert _total_mass(root) == pytest.approx(TABLE_I_MASS, abs=1e-9)  # belts keep their mass


def test_without_gripper_the_gripper_is_gone():
    root = _expand(with_gripper="false", main_track_wheels=2, flipper_track_wheels=2)
    assert not [j for j in _joints(root) if j.get("name").endswith("_ee")]
    assert _total_mass(root) == pytest.approx(TABLE_I_MASS - GRIPPER_MASS, abs=1e-9)


def test_gripper_has_six_joints_five_mimicking_the_driver(robot):
    gripper = [j for j in _joints(robot) if j.get("name").endswith("_ee")]
    assert len(gripper) == 6
    mimics = [j for j in gripper if j.find("mimic") is not None]
    assert len(mimics) == 5
    assert {j.find("mimic").get("joint") for j in mimics} == {"p1_left_ee"}


def test_flippers_move_in_sync(robot):
    right = robot.find("joint[@name='right_flipper']")
    assert right.find("mimic").get("joint") == "left_flipper"
    assert float(right.find("mimic").get("multiplier")) == 1.0


def test_four_cameras_each_with_an_optical_frame(robot):
    parents = {j.find("child").get("link"): j.find("parent").get("link") for j in _joints(robot)}
    cameras = [f"camera{n}_link" for n in range(1, 5)]
    for camera in cameras:
        assert parents[f"{camera}_optical"] == camera
        plugin = robot.find(f"gazebo[@reference='{camera}']/sensor/plugin")
        assert plugin.get("filename") == "libgazebo_ros_camera.so"
        assert plugin.findtext("frameName") == f"{camera}_optical"


def test_inertias_are_physical_and_moving_links_have_them(robot):
    moving_children = {j.find("child").get("link") for j in _joints(robot) if j.get("type") != "fixed"}
    for link in robot.findall("link"):
        inertia = link.find("inertial/inertia")
        if inertia is None:
            assert link.get("name") not in moving_children, link.get("name")
            continue
        v = {k: float(inertia.get(k)) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
        matrix = np.array([[v["ixx"], v["ixy"], v["ixz"]], [v["ixy"], v["iyy"], v["iyz"]],
                           [v["ixz"], v["iyz"], v["izz"]]])
        a, b, c = np.linalg.eigvalsh(matrix)
        assert a > 0, link.get("name")
        assert a + b >= c * (1 - 1e-9), link.get("name")


def test_joint_hygiene(robot):
    for joint in _joints(robot):
        kind, limit, axis = joint.get("type"), joint.find("limit"), joint.find("axis")
        if kind == "fixed":
            continue
        assert np.linalg.norm([float(x) for x in axis.get("xyz").split()]) == pytest.approx(1.0)
        assert float(limit.get("effort")) > 0 and float(limit.get("velocity")) > 0
        if kind == "revolute":
            assert float(limit.get("lower")) <= float(limit.get("upper"))
        if kind == "continuous":
            assert limit.get("lower") is None and limit.get("upper") is None


def test_transmissions_cover_every_driven_joint(robot):
    driven = {j.get("name") for j in _joints(robot) if j.get("type") != "fixed" and j.find("mimic") is None}
    transmitted = {t.find("joint").get("name") for t in robot.findall("transmission")}
    assert transmitted == driven
    for transmission in robot.findall("transmission"):
        assert transmission.findtext("type") == "transmission_interface/SimpleTransmission"
        assert transmission.findtext("actuator/mechanicalReduction") == "1"


def test_references_meshes_and_materials_exist(robot):
    links = {link.get("name") for link in robot.findall("link")}
    joints = {joint.get("name") for joint in robot.findall("joint")}
    for gazebo in robot.findall("gazebo[@reference]"):
        assert gazebo.get("reference") in links | joints
    assert robot.find("gazebo[@reference='head_link']/light").get("type") == "spot"
    materials = {m.get("name") for m in robot.findall("material")}
    for material in robot.findall("link/visual/material"):
        assert material.get("name") in materials
    files = {p.relative_to(PACKAGE).as_posix() for p in (PACKAGE / "meshes").rglob("*.stl")}
    for mesh in robot.iter("mesh"):
        uri = mesh.get("filename")
        assert uri.startswith("package://engineer_description/meshes/"), uri
        # exact case, unlike the paper's Cronstain.dae
        assert uri.removeprefix("package://engineer_description/") in files, uri


def test_track_controllers_name_existing_wheels(robot):
    yaml = pytest.importorskip("yaml")
    config = yaml.safe_load((CONTROL / "config" / "engineer_tracks.yaml").read_text())
    joints = {j.get("name") for j in _joints(robot)}
    for controller in config.values():
        assert set(controller["left_wheel"]) | set(controller["right_wheel"]) <= joints


def test_wheel_loop_recursion_stays_logarithmic(default_expansion):
    depths = {r.macro: r.depth for r in default_expansion.macro_recursion}
    assert depths.get("track_wheel_range", 0) <= 8  # halving: about log2(56) + 1, not 56


def test_pinocchio_builds_the_model_with_mass_and_mimics(default_expansion):
    pin = pytest.importorskip("pinocchio", reason="pinocchio (pin) is not installed")
    from robotdesc.source import PROVENANCE_ATTR
    root = etree.fromstring(default_expansion.xml)
    for element in root.iter():
        element.attrib.pop(PROVENANCE_ATTR, None)
    model = pin.buildModelFromXML(etree.tostring(root).decode(), pin.JointModelFreeFlyer(), mimic=True)
    assert pin.computeTotalMass(model) == pytest.approx(TABLE_I_MASS, abs=1e-6)
    assert len(model.mimicking_joints) == 6  # five in the gripper, one flipper


# ----------------------------------------------------------------------------- robotdesc on the package

VARIANTS = [{}, {"main_track_wheels": "18", "flipper_track_wheels": "31"}, {"with_gripper": "false"},
            {"with_gripper": "false", "main_track_wheels": "18", "flipper_track_wheels": "31"}]


@pytest.mark.slow
@pytest.mark.parametrize("args", VARIANTS, ids=lambda a: ",".join(f"{k}={v}" for k, v in a.items()) or "default")
def test_lints_clean_with_every_rule(args):
    """The acceptance line of the package: no finding at all, every rule family enabled, with
    the package's own robotdesc.toml (which sets the expected mass and no lint setting)."""
    import robotdesc

    result = robotdesc.lint(str(TOP), args=args)
    assert [f"{d.code} {d.message}" for d in result.diagnostics] == []


def test_package_config_sets_the_mass_and_hides_nothing():
    from robotdesc.config import discover_config

    try:
        import tomllib
    except ImportError:  # Python 3.10
        tomllib = pytest.importorskip("tomli")

    config = discover_config(str(TOP))
    assert config.meshes.expected_mass == pytest.approx(TABLE_I_MASS)
    assert config.meshes.inertia_source == "collision"
    with open(PACKAGE / "robotdesc.toml", "rb") as stream:
        table = tomllib.load(stream)
    assert set(table) == {"meshes", "targets", "sim"}  # no ignore, select, severity, rules,
    assert table["meshes"] == {"expected-mass": TABLE_I_MASS}  # fail-on
    # the drive test's skid-steer correction in MuJoCo (DART's is the controllers file's)
    assert table["sim"] == {"separation-multiplier": {"mujoco": 2.5}}


def test_no_link_pair_overlaps_at_the_default_configuration():
    pytest.importorskip("pinocchio", reason="pinocchio (pin) is not installed")
    import robotdesc
    from robotdesc.mesh.locate import MeshLocator
    from robotdesc.srdf.matrix import default_collisions, prepare_scene

    robot = robotdesc.load(str(TOP), args={"main_track_wheels": "56", "flipper_track_wheels": "50"})
    prepared = prepare_scene(robot, MeshLocator.for_robot(robot, origin=str(TOP)).path)
    assert default_collisions(prepared) == []
    assert not prepared.problems


@pytest.mark.slow
def test_srdf_command_writes_a_collision_matrix(tmp_path):
    pytest.importorskip("pinocchio", reason="pinocchio (pin) is not installed")
    from robotdesc.cli import main

    out = tmp_path / "engineer.srdf"
    code = main(["srdf", str(TOP), "main_track_wheels:=18", "flipper_track_wheels:=31",
                 "--samples", "200", "--seed", "1", "--jobs", "1", "-o", str(out)])
    assert code == 0
    srdf = etree.parse(str(out)).getroot()
    reasons = {d.get("reason") for d in srdf.findall("disable_collisions")}
    assert "Adjacent" in reasons and "Never" in reasons
    assert "Default" not in reasons  # nothing collides at the default configuration
