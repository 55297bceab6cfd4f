"""One root, one module: every error robotdesc raises on purpose is a `RobotdescError` from
`robotdesc.errors`, with typed fields, and the public collision API raises them (not a bare
ValueError) for what a user passes in."""

from __future__ import annotations

import ast
import importlib
import inspect
import pickle
from pathlib import Path

import numpy as np
import pytest

from robotdesc import errors
from robotdesc.cli import main
from robotdesc.errors import (
    CollisionOptionError,
    GeometryError,
    InputError,
    NoVolumeError,
    OptionError,
    RobotdescError,
    SettingError,
    UnknownLinkError,
    UsageError,
    XmlSyntaxError,
)
from robotdesc.model.elements import Box, Capsule, Cylinder, Sphere
from robotdesc.model.parse import parse_urdf

SRC = Path(__file__).resolve().parent.parent / "src" / "robotdesc"

#: Error classes that moved into robotdesc.errors: each old home still re-exports its class.
MOVED = {"robotdesc.sim.meshes": ["SimMeshError"],
         "robotdesc.sim.run": ["SimMeshError"],
         "robotdesc.kinematics.build": ["KinematicBuildError", "BuildProblem"],
         "robotdesc.kinematics.optional": ["KinematicsUnavailable", "PINOCCHIO_HINT"],
         "robotdesc.kinematics": ["KinematicsUnavailable", "PINOCCHIO_HINT"]}

ERROR_CLASSES = [cls for _, cls in inspect.getmembers(errors, inspect.isclass)
                 if issubclass(cls, BaseException) and cls.__module__ == errors.__name__]


def test_every_error_class_of_the_module_derives_from_the_root() -> None:
    assert len(ERROR_CLASSES) > 20
    for cls in ERROR_CLASSES:
        assert issubclass(cls, RobotdescError), cls


def test_input_errors_exit_2_and_bugs_exit_3() -> None:
    for cls in ERROR_CLASSES:
        assert cls.exit_code == (2 if issubclass(cls, InputError) else 3), cls
    assert {cls.__name__ for cls in ERROR_CLASSES if not issubclass(cls, InputError)} == {
        "RobotdescError", "RuleCrashed", "WorkerCrashed"}


def test_no_other_module_defines_a_robotdesc_error() -> None:
    names = {cls.__name__ for cls in ERROR_CLASSES}
    found = set()
    for path in SRC.rglob("*.py"):
        if path == SRC / "errors.py":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ClassDef) and any(
                    (base.id if isinstance(base, ast.Name) else
                     base.attr if isinstance(base, ast.Attribute) else "") in names
                    for base in node.bases):
                found.add(f"{path.relative_to(SRC).as_posix()}:{node.name}")
    assert found == set()


@pytest.mark.parametrize("module", sorted(MOVED))
def test_moved_errors_live_in_the_errors_module_and_keep_their_old_import_paths(
        module: str) -> None:
    old_home = importlib.import_module(module)
    for name in MOVED[module]:
        assert getattr(old_home, name) is getattr(errors, name), (module, name)
        assert name in old_home.__all__, (module, name)
    for cls in (errors.SimMeshError, errors.KinematicBuildError, errors.KinematicsUnavailable):
        assert cls.__module__ == errors.__name__ and cls in ERROR_CLASSES
        assert issubclass(cls, InputError) and cls.exit_code == 2


@pytest.mark.parametrize("error", [
    errors.MeshError(errors.MeshErrorKind.EMPTY, "is empty", "a.stl"),
    errors.PackageNotFoundError("pkg", None, ("/opt",)),
    errors.OutputError("out.urdf", "it is an input"),
    CollisionOptionError("ratio", 2.0, "ratio must be in (0, 1], got 2.0"),
    errors.SimOptionError("seconds", 0, "seconds must be positive, got 0"),
    SettingError("mass-tolerance", 2.0, "mass-tolerance must be in [0, 1), got 2.0"),
    GeometryError("bad box", shape="box", dimensions=(0.0, 1.0, 1.0)),
    NoVolumeError("3 distinct points span no volume"),
    UnknownLinkError(("nope",), "no link with visual geometry named nope"),
    errors.OutputConflict("refusing to overwrite", None, ("a.stl",)),
    errors.SimUnavailable("mujoco", "mujoco>=3.3", "install it"),
    errors.SimModelError("no tree", None, "base"),
    errors.DriveConfigError("no wheels", group="base", joint="left"),
    errors.SimMeshError("cannot simulate: a.stl does not resolve"),
    errors.KinematicsUnavailable("robotdesc info"),
    errors.KinematicBuildError(errors.BuildProblem("joint [knee] has no limit", "joint:knee")),
    errors.KinematicBuildError(errors.BuildProblem("no root link", from_pinocchio=False)),
    errors.RuleCrashed("X101", "name", "robot.urdf", RuntimeError("boom")),
    errors.WorkerCrashed("robot.urdf", "RuntimeError: boom", "Traceback ..."),
])
def test_errors_pickle_with_their_fields(error: RobotdescError) -> None:
    """Errors travel back from worker processes (lint --jobs, collision workers)."""
    copy = pickle.loads(pickle.dumps(error))
    assert type(copy) is type(error) and str(copy) == str(error)
    assert vars(copy) == vars(error)


def test_bad_values_are_usage_errors_and_value_errors() -> None:
    """Typed, with exit code 2; still caught by code that catches ValueError."""
    for cls in (OptionError, CollisionOptionError, errors.SimOptionError, UnknownLinkError):
        assert issubclass(cls, UsageError) and issubclass(cls, ValueError)
    assert issubclass(SettingError, errors.ConfigError) and issubclass(SettingError, ValueError)
    assert issubclass(NoVolumeError, GeometryError) and issubclass(GeometryError, ValueError)
    assert not issubclass(XmlSyntaxError, ValueError)


# --- the public collision API -------------------------------------------------------------


@pytest.mark.parametrize("change, option", [
    ({"method": "magic"}, "method"), ({"ratio": 0.0}, "ratio"), ({"faces": 3}, "faces"),
    ({"decimator": "blender"}, "decimator"), ({"threshold": 2.0}, "threshold"),
    ({"max_hulls": 0}, "max_hulls"), ({"coacd_depth": 0}, "coacd_depth"),
    ({"coacd_input_faces": 2}, "coacd_input_faces"), ({"hull_vertices": 3}, "hull_vertices"),
    ({"primitives": ("cone",)}, "primitives"), ({"auto_order": ("auto",)}, "auto_order"),
    ({"samples": 5}, "samples"), ({"target_percent": 0.0}, "target_percent"),
    ({"mesh_timeout_s": 0.0}, "mesh_timeout_s"), ({"source": "inertial"}, "source"),
])
def test_collision_options_name_the_bad_option(change: dict, option: str) -> None:
    from robotdesc.collision.options import CollisionOptions

    with pytest.raises(CollisionOptionError) as caught:
        CollisionOptions(**change).validated()
    assert caught.value.option == option
    assert caught.value.value == next(iter(change.values()))


@pytest.mark.parametrize("limit, value", [("max_hulls", 0), ("max_hull_vertices", 3),
                                          ("max_mesh_faces", 2)])
def test_engine_limits_are_checked_with_the_options(limit: str, value: int) -> None:
    from robotdesc.collision.limits import EngineLimits
    from robotdesc.collision.options import CollisionOptions

    with pytest.raises(CollisionOptionError) as caught:
        CollisionOptions(limits=EngineLimits("custom", **{limit: value})).validated()
    assert caught.value.option == f"limits.{limit}" and caught.value.value == value


BOX_ROBOT = b"""<robot name="r"><link name="base"><visual><geometry><box size="0.1 0.2 0.3"/>
  </geometry></visual></link></robot>"""


def test_generate_collision_refuses_an_unknown_link(tmp_path: Path) -> None:
    from robotdesc.collision.generate import generate_collision

    robot = parse_urdf(BOX_ROBOT, str(tmp_path / "r.urdf"))
    with pytest.raises(UnknownLinkError) as caught:
        generate_collision(robot, links=["base", "nope"], use_cache=False)
    assert caught.value.links == ("nope",)
    with pytest.raises(CollisionOptionError):
        generate_collision(robot, method="magic", use_cache=False)


@pytest.mark.parametrize("geometry, shape", [(Box((0.0, 1.0, 1.0)), "box"),
                                             (Sphere(float("nan")), "sphere"),
                                             (Cylinder(-1.0, 1.0), "cylinder"),
                                             (Capsule(0.0, 1.0), "capsule")])
def test_a_primitive_with_a_bad_dimension_is_a_geometry_error(geometry, shape: str) -> None:
    pytest.importorskip("trimesh")
    from robotdesc.collision.tessellate import primitive_mesh

    with pytest.raises(GeometryError) as caught:
        primitive_mesh(geometry)
    assert caught.value.shape == shape and len(caught.value.dimensions) >= 1


def test_hulls_distances_and_decimation_raise_typed_errors() -> None:
    pytest.importorskip("scipy")
    from robotdesc.collision.decimate import decimate
    from robotdesc.collision.distance import SurfaceIndex
    from robotdesc.collision.hull import convex_hull, reduce_hull

    flat = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]])
    with pytest.raises(NoVolumeError):
        convex_hull(flat)
    with pytest.raises(NoVolumeError):
        convex_hull(flat[:3])
    cube = np.array([[x, y, z] for x in (0.0, 1) for y in (0.0, 1) for z in (0.0, 1)])
    hull = convex_hull(cube)
    with pytest.raises(CollisionOptionError) as caught:
        reduce_hull(hull, 3)
    assert caught.value.option == "max_hull_vertices"
    with pytest.raises(GeometryError):
        SurfaceIndex(cube, np.zeros((0, 3), dtype=np.int64))
    with pytest.raises(CollisionOptionError) as caught:
        decimate(hull.vertices, hull.faces, 4, engine="blender")
    assert (caught.value.option, caught.value.value) == ("decimator", "blender")


def test_unpairable_xml_is_an_xml_syntax_error() -> None:
    from robotdesc.collision.xml_extent import element_extents

    with pytest.raises(XmlSyntaxError, match="line 1"):
        element_extents("<a><b></a>")


def test_mesh_mass_and_settings_raise_typed_errors() -> None:
    from robotdesc.mesh.mass import volume_integrals
    from robotdesc.mesh.primitives import primitive_properties
    from robotdesc.mesh.settings import MeshSettings

    with pytest.raises(GeometryError) as caught:
        primitive_properties(Box((-1.0, 1.0, 1.0)))
    assert caught.value.shape == "box" and caught.value.dimensions == (-1.0, 1.0, 1.0)
    tetra = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    outward = tetra[[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]]
    assert volume_integrals(outward).volume > 0
    with pytest.raises(GeometryError, match="not positive"):
        volume_integrals(outward[:, ::-1]).properties()
    with pytest.raises(SettingError) as setting:
        MeshSettings(mass_tolerance=2.0)
    assert (setting.value.key, setting.value.value) == ("mass-tolerance", 2.0)


def test_a_bad_mesh_setting_in_the_config_still_names_the_file(tmp_path: Path) -> None:
    from robotdesc.config import load_config

    path = tmp_path / "robotdesc.toml"
    path.write_text("[meshes]\nmass-tolerance = 2.0\n")
    with pytest.raises(errors.ConfigError) as caught:
        load_config(str(path))
    assert str(path) in str(caught.value) and "mass-tolerance" in str(caught.value)


# --- the command line: exit 2 and a message, never a traceback ----------------------------


@pytest.mark.parametrize("args, message", [
    (["--check", "--out", "OUT", "--link", "nope"], "no link with visual geometry named nope"),
    (["--dry-run", "--link", "nope"], "no link with visual geometry named nope"),
    (["--dry-run", "--method", "hull", "--limit-hull-vertices", "2"],
     "the limit of vertices per hull must be at least 4"),
    (["--dry-run", "--ratio", "2"], "ratio must be in (0, 1], got 2.0"),
])
def test_collision_cli_refuses_bad_input_with_exit_2(tmp_path: Path, capsys, args: list,
                                                     message: str) -> None:
    urdf = tmp_path / "r.urdf"
    urdf.write_bytes(BOX_ROBOT)
    args = [str(tmp_path / "out") if a == "OUT" else a for a in args]
    code = main(["collision", str(urdf), "--no-cache", *args])
    err = capsys.readouterr().err
    assert code == 2, err
    assert message in err and "internal error" not in err and "Traceback" not in err

