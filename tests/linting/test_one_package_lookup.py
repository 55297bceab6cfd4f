"""One package lookup per lint target: the rules' meshes and the run's inputs (the files no
output may replace, the result cache's completeness) resolve packages through the lookup
`lint_target` builds, never through one rebuilt at each use."""

from __future__ import annotations

from pathlib import Path

import pytest

from robotdesc.expansion import ExpandOptions
from robotdesc.expansion import packages as package_module
from robotdesc.linting import parallel
from robotdesc.linting.targets import LintTarget
from robotdesc.mesh import context, locate
from robotdesc.mesh.resolve import PackageLookup

URDF = """<robot name="arm"><link name="base"><visual><geometry>
<mesh filename="package://arm/meshes/base.stl"/></geometry></visual></link></robot>"""


def test_lint_target_builds_one_package_lookup(tmp_path: Path,
                                               monkeypatch: pytest.MonkeyPatch) -> None:
    package = tmp_path / "arm"
    (package / "meshes").mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>arm</name></package>")
    (package / "meshes" / "base.stl").write_bytes(b"solid x\nendsolid x\n")
    (package / "arm.urdf").write_text(URDF)
    built: list[str] = []

    def counted(origin: str, *args: object, **kwargs: object) -> PackageLookup:
        built.append(origin)
        return package_module.package_lookup(origin, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(parallel, "package_lookup", counted)
    monkeypatch.setattr(context, "package_lookup", counted)
    monkeypatch.setattr(locate, "package_lookup", counted)
    result = parallel.lint_target(LintTarget(str(package / "arm.urdf")), {},
                                  ExpandOptions(use_cache=False), None, ())
    assert built == [str(package / "arm.urdf")]
    assert result.inputs is not None
    mesh = str((package / "meshes" / "base.stl").resolve())
    assert mesh in {item.path for item in result.inputs.items}
