"""P101/P102 carry their fix as data: the path as package://PACKAGE/PATH of the package that
holds the file, or why not (the file is in no ROS package)."""

from __future__ import annotations

from pathlib import Path

from robotdesc.diagnostics import Finding, ValueChange
from robotdesc.model.parse import parse_urdf
from robotdesc.rules.catalog import get_rule
from robotdesc.rules.registry import ExpansionFacts, RuleContext


def findings(filename: str) -> list[Finding]:
    robot = parse_urdf(f"""<robot name="arm"><link name="base"><visual><geometry>
<mesh filename="{filename}"/></geometry></visual></link></robot>""".encode(), "arm.urdf")
    found: list[Finding] = []
    for name in ("absolute-mesh-path", "file-uri-mesh"):
        found += get_rule(name).check(robot, RuleContext(expansion=ExpansionFacts()))
    return found


def test_a_path_in_a_package_becomes_package_uri(tmp_path: Path) -> None:
    (tmp_path / "arm").mkdir()
    (tmp_path / "arm" / "package.xml").write_text("<package><name>arm</name></package>")
    for filename in (f"{tmp_path}/arm/meshes/base.stl", f"file://{tmp_path}/arm/meshes/base.stl"):
        [finding] = findings(filename)
        assert finding.changes == (ValueChange("link:base/visual[0]/geometry/mesh", "filename",
                                               "package://arm/meshes/base.stl"),)
        assert finding.unfixable == ""


def test_a_path_in_no_package_says_why_not(tmp_path: Path) -> None:
    [finding] = findings(f"{tmp_path}/meshes/base.stl")
    assert finding.changes == ()
    assert "is in no ROS package (no package.xml above it)" in finding.unfixable
