"""A warm lint (every mesh summary in the cache) must not import numpy, trimesh or scipy,
and the package's lazy exports must all resolve."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import robotdesc.mesh

from .builders import box_triangles, write_binary_stl

URDF = """<?xml version="1.0"?>
<robot name="r">
  <link name="base"/>
  <link name="arm">
      <inertial><origin xyz="0 0 0.1"/><mass value="2"/>
      <inertia ixx="8.3" ixy="0" ixz="0" iyy="8.3" iyz="0" izz="3.3"/></inertial>
    <visual><origin xyz="0 0 0.1" rpy="0 0.2 0"/>
      <geometry><mesh filename="package://pkg/box.stl" scale="0.1 0.1 0.1"/></geometry></visual>
    <collision><origin xyz="0 0 0.1" rpy="0 0.2 0"/>
      <geometry><mesh filename="package://pkg/box.stl" scale="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""

LINT = """
import sys
from robotdesc.linting.driver import lint_file
result = lint_file(sys.argv[1], ignore=["K"])
heavy = sorted(m for m in sys.modules if m.split(".")[0] in ("numpy", "trimesh", "scipy"))
print(",".join(sorted({d.code for d in result.diagnostics})))
print(",".join(heavy))
"""


def _lint(urdf: Path, cache: Path) -> list[str]:
    env = dict(os.environ, ROBOTDESC_CACHE_DIR=str(cache),
               PYTHONPATH=os.pathsep.join([str(Path(robotdesc.mesh.__file__).parents[2]),
                                          os.environ.get("PYTHONPATH", "")]))
    done = subprocess.run([sys.executable, "-c", LINT, str(urdf)], capture_output=True,
                          text=True, env=env, check=True, cwd=urdf.parent)
    return done.stdout.splitlines()


def test_a_warm_lint_imports_no_numpy(tmp_path: Path) -> None:
    package = tmp_path / "pkg"
    package.mkdir()
    (package / "package.xml").write_text("<package><name>pkg</name></package>")
    write_binary_stl(package / "box.stl", box_triangles((1.0, 1.0, 2.0)))
    urdf = package / "r.urdf"
    urdf.write_text(URDF)
    cold = _lint(urdf, tmp_path / "cache")
    warm = _lint(urdf, tmp_path / "cache")
    assert "numpy" in cold[1]  # the cold run measured the mesh
    assert warm[0] == cold[0] and "I204" in warm[0]  # same findings, mesh rules ran
    assert warm[1] == ""


def test_lazy_exports_resolve() -> None:
    for name in robotdesc.mesh.__all__:
        assert getattr(robotdesc.mesh, name) is not None
