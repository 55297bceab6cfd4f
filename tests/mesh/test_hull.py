"""robotdesc.mesh.hull: the convex hull's triangles are wound outward, close, and give the
mass properties scipy's qhull gives (scipy is installed with the tests, not used by the
code); flat, collinear and too-small point sets have no hull; a lint of a mesh that needs
the hull imports no scipy."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial import ConvexHull  # a dependency of robotdesc (collision); lint never imports it

import robotdesc.mesh
from robotdesc.mesh.hull import convex_hull_faces
from robotdesc.mesh.mass import volume_integrals
from robotdesc.mesh.properties import MassProperties

from .builders import box_triangles, write_binary_stl


def _properties(points: np.ndarray, faces: np.ndarray) -> MassProperties:
    return volume_integrals(points[faces]).properties()


def _qhull_properties(points: np.ndarray) -> MassProperties:
    hull = ConvexHull(points)
    soup = points[hull.simplices]
    normal = np.cross(soup[:, 1] - soup[:, 0], soup[:, 2] - soup[:, 0])
    inward = np.einsum("ij,ij->i", normal, hull.equations[:, :3]) < 0
    soup[inward] = soup[inward][:, ::-1]
    return volume_integrals(soup).properties()


def _assert_closed_and_outward(points: np.ndarray, faces: np.ndarray) -> None:
    """Every directed edge once and its reverse once; no repeated corner; every point on or
    below every face whose plane its corners fix (not a sliver of nearly collinear points,
    which a flat side rounded to float32 can need)."""
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    assert len({tuple(e) for e in edges.tolist()}) == len(edges)
    assert {tuple(e) for e in edges.tolist()} == {tuple(e) for e in edges[:, ::-1].tolist()}
    assert ((faces != np.roll(faces, 1, axis=1)).all())
    corners = points[faces]
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    longest = (np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=2) ** 2).max(axis=1)
    length = np.linalg.norm(normal, axis=1)
    fixed = length > 1e-6 * longest
    corners, normal = corners[fixed], normal[fixed] / length[fixed, None]
    heights = np.einsum("fj,pfj->pf", normal, points[:, None, :] - corners[None, :, 0, :])
    extent = float(np.abs(points - points.mean(axis=0)).max())
    assert heights.max() <= 1e-9 * extent


def _assert_like_qhull(points: np.ndarray, relative: float = 1e-9) -> None:
    faces = convex_hull_faces(points)
    assert faces is not None
    _assert_closed_and_outward(points, faces)
    ours, theirs = _properties(points, faces), _qhull_properties(points)
    side = float(np.ptp(points, axis=0).max())
    assert ours.volume == pytest.approx(theirs.volume, rel=relative)
    assert np.abs(np.subtract(ours.center_of_mass, theirs.center_of_mass)).max() \
        <= relative * side
    inertia = np.abs(np.asarray(theirs.inertia)).max()
    assert np.abs(np.subtract(ours.inertia, theirs.inertia)).max() <= relative * inertia


def _box_surface_grid(size: tuple[float, float, float], steps: int) -> np.ndarray:
    """Points of a regular grid on the six faces of a box (all coplanar in sixes)."""
    axes = [np.linspace(0.0, s, steps) for s in size]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    on_face = np.isclose(grid, 0.0).any(axis=1) | np.isclose(grid, size).any(axis=1)
    return grid[on_face]


def test_cube_and_tetrahedron() -> None:
    cube = np.array([[x, y, z] for x in (0.0, 1) for y in (0.0, 1) for z in (0.0, 1)])
    faces = convex_hull_faces(cube)
    assert faces is not None and len(faces) == 12
    props = _properties(cube, faces)
    assert props.volume == pytest.approx(1.0, rel=1e-12)
    assert props.center_of_mass == pytest.approx((0.5, 0.5, 0.5), rel=1e-12)
    assert np.diag(props.inertia) == pytest.approx([1 / 6] * 3, rel=1e-12)
    tetrahedron = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    faces = convex_hull_faces(tetrahedron)
    assert faces is not None and len(faces) == 4
    assert _properties(tetrahedron, faces).volume == pytest.approx(1 / 6, rel=1e-12)
    _assert_like_qhull(tetrahedron)


@pytest.mark.parametrize("seed", range(4))
def test_random_clouds_match_qhull(seed: int) -> None:
    rng = np.random.default_rng(seed)
    _assert_like_qhull(rng.uniform(-1.0, 1.0, (2000, 3)))
    sphere = rng.normal(size=(3000, 3))  # every point on the hull
    _assert_like_qhull(sphere / np.linalg.norm(sphere, axis=1)[:, None])
    _assert_like_qhull(rng.normal(size=(40, 3)) * [5.0, 0.1, 1.0])  # thin, few points


@pytest.mark.parametrize("seed", range(4))
def test_a_thin_slab_matches_qhull(seed: int) -> None:
    """Points 1e-8 as thick as wide: the tolerance must stay below the slab's own rounding
    (1e-12 of the width lost up to 2e-6 of its volume)."""
    rng = np.random.default_rng(seed)
    _assert_like_qhull(rng.uniform(-1.0, 1.0, (3000, 3)) * [1.0, 1.0, 1e-8])


@pytest.mark.parametrize("seed", range(12))
def test_a_turned_lattice_in_float32_matches_qhull(seed: int) -> None:
    """A cubic lattice turned at random and rounded to float32: rows of nearly collinear
    points on nearly flat sides, where an eye lands on the line of a rim edge (a new face
    of no area: the face beyond is taken instead)."""
    rng = np.random.default_rng(seed)
    turn = np.linalg.qr(rng.normal(size=(3, 3)))[0]
    steps = np.linspace(-1.0, 1.0, int(rng.integers(3, 15)))
    lattice = np.stack(np.meshgrid(steps, steps, steps), axis=-1).reshape(-1, 3)
    _assert_like_qhull((lattice @ turn.T).astype(np.float32).astype(np.float64)
                       * rng.uniform(1e-3, 1e3))


def test_coplanar_heavy_and_duplicate_points_match_qhull() -> None:
    box = _box_surface_grid((1.0, 2.0, 3.0), 13)
    faces = convex_hull_faces(box)
    assert faces is not None
    assert _properties(box, faces).volume == pytest.approx(6.0, rel=1e-12)
    _assert_like_qhull(box)
    doubled = np.concatenate([box, box[::3], box[::7]])
    _assert_like_qhull(doubled)
    soup = box_triangles((0.2, 0.3, 0.4), center=(1.0, -2.0, 0.5)).reshape(-1, 3)
    _assert_like_qhull(soup)  # a soup: every corner six times


@pytest.mark.parametrize("seed", range(8))
def test_float32_noise_on_flat_sides_stays_convex(seed: int) -> None:
    """A box's sides as CAD exports them: grid points in float32, some off their plane by a
    float32 step, so that rows of nearly collinear points on the rims make cone faces that
    are slivers; the hull must not fold back over a face it is level with (seen on a
    Clearpath mesh: a fold 3e-8 deep)."""
    rng = np.random.default_rng(seed)
    box = _box_surface_grid((1.0, 0.7, 0.3), 9) - 0.4
    box = box + rng.choice([0.0, 0.0, 3e-8, -3e-8], size=box.shape)
    _assert_like_qhull(box.astype(np.float32).astype(np.float64))


@pytest.mark.parametrize("scale, offset", [(1e-6, 0.0), (1e-6, 1.0), (1e4, 0.0), (1e3, 1e5)])
def test_tiny_and_huge_coordinates(scale: float, offset: float) -> None:
    rng = np.random.default_rng(5)
    cloud = rng.uniform(-1.0, 1.0, (500, 3))
    box = _box_surface_grid((1.0, 1.0, 2.0), 7)
    for points in (cloud, box):
        _assert_like_qhull(points * scale + offset, relative=1e-8)


def test_blocks_of_points_give_the_same_hull(monkeypatch: pytest.MonkeyPatch) -> None:
    """Steps that touch every point go a block at a time (meshes of millions of points);
    tiny blocks give the same hull."""
    from robotdesc.mesh import hull

    rng = np.random.default_rng(2)
    cloud = np.concatenate([rng.normal(size=(1500, 3)), _box_surface_grid((2.0, 1.0, 1.0), 9)])
    expected = convex_hull_faces(cloud)
    monkeypatch.setattr(hull, "_BLOCK", 7)
    found = convex_hull_faces(cloud)
    assert expected is not None and found is not None
    assert _properties(cloud, found).volume == pytest.approx(
        _properties(cloud, expected).volume, rel=1e-12)
    _assert_like_qhull(cloud)


def test_no_volume_no_hull() -> None:
    rng = np.random.default_rng(3)
    plane = np.column_stack([rng.uniform(0, 1, (100, 2)), np.full(100, 0.3)])
    tilted = plane @ np.array([[1.0, 0.2, 0.5], [0.3, 1.0, 0.1], [0.0, 0.0, 1.0]])
    line = np.outer(rng.uniform(-1, 1, 50), [1.0, 2.0, -0.5]) + [3.0, 0.0, 1.0]
    same = np.tile([[1.0, 2.0, 3.0]], (10, 1))
    for points in (plane, tilted, line, same, plane[:3], np.zeros((0, 3))):
        assert convex_hull_faces(points) is None
    assert convex_hull_faces(np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [np.nan, 0, 1]])) \
        is None


LINT = """
import sys
from robotdesc.linting.driver import lint_file
result = lint_file(sys.argv[1], ignore=["K"])
print(",".join(sorted({d.code for d in result.diagnostics})))
print(",".join(sorted(m for m in sys.modules if m.split(".")[0] == "scipy")))
"""

URDF = """<?xml version="1.0"?>
<robot name="r">
  <link name="base"/>
  <link name="arm">
    <inertial><mass value="2"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
    <visual><geometry><mesh filename="package://pkg/open.stl"/></geometry></visual>
    <collision><geometry><mesh filename="package://pkg/open.stl"/></geometry></collision>
  </link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""


def test_a_lint_of_a_mesh_that_needs_the_hull_imports_no_scipy(tmp_path: Path) -> None:
    """An open, misoriented mesh (its mass properties from the hull), more than 2048 rim
    points (the old k-d tree's threshold), the mesh cache empty."""
    package = tmp_path / "pkg"
    package.mkdir()
    (package / "package.xml").write_text("<package><name>pkg</name></package>")
    rng = np.random.default_rng(11)
    sphere = rng.normal(size=(3000, 3))
    sphere = 0.1 * sphere / np.linalg.norm(sphere, axis=1)[:, None]
    triangles = sphere[rng.integers(0, len(sphere), (3000, 3))]  # a misoriented soup
    soup = np.concatenate([box_triangles((0.1, 0.1, 0.1))[1:], triangles])
    write_binary_stl(package / "open.stl", soup)
    urdf = package / "r.urdf"
    urdf.write_text(URDF)
    env = dict(os.environ, ROBOTDESC_CACHE_DIR=str(tmp_path / "cache"),
               PYTHONPATH=os.pathsep.join([str(Path(robotdesc.mesh.__file__).parents[2]),
                                          os.environ.get("PYTHONPATH", "")]))
    done = subprocess.run([sys.executable, "-c", LINT, str(urdf)], capture_output=True,
                          text=True, env=env, check=True, cwd=tmp_path)
    scipy_modules = done.stdout.splitlines()[1]
    assert scipy_modules == ""
    stored = [path.read_text() for path in (tmp_path / "cache").rglob("*.json")]
    assert any('"convex-hull"' in text for text in stored)  # the lint used the hull
