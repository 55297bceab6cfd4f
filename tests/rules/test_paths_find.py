"""P101/P102 stay silent on a path that `$(find pkg)` made while expanding the xacro
(doosan's and xArm's `file://$(find pkg)/meshes/...`, held-out packages): the source is
portable. A path written out in the source is still reported."""

from __future__ import annotations

import pytest

from robotdesc.model.parse import parse_urdf
from robotdesc.rules.catalog import get_rule
from robotdesc.rules.registry import ExpansionFacts, RuleContext

PACKAGE = "/home/ana/ws/src/arm_description"


def robot(filename: str):
    return parse_urdf(f"""<robot name="arm"><link name="base"><visual><geometry>
<mesh filename="{filename}"/></geometry></visual></link></robot>""".encode(), "arm.urdf")


def codes(filename: str, facts: ExpansionFacts) -> list[str]:
    found = []
    for name in ("absolute-mesh-path", "file-uri-mesh"):
        rule = get_rule(name)
        found += [rule.code for _ in rule.check(robot(filename), RuleContext(expansion=facts))]
    return found


MADE = ExpansionFacts(from_xacro=True, package_folders=(PACKAGE,))


@pytest.mark.parametrize("filename", [f"file://{PACKAGE}/meshes/base.stl",
                                      f"file:///{PACKAGE}/meshes/base.stl",
                                      f"{PACKAGE}/meshes/base.stl"])
def test_a_path_find_made_is_not_reported(filename: str) -> None:
    assert codes(filename, MADE) == []


@pytest.mark.parametrize(("filename", "facts", "expected"), [
    ("file:///opt/arm/meshes/base.stl", MADE, ["P102"]),
    (f"file://{PACKAGE}_other/meshes/base.stl", MADE, ["P102"]),
    ("/opt/arm/meshes/base.stl", MADE, ["P101"]),
    # a plain URDF: nothing was made by $(find), the path is written out
    (f"file://{PACKAGE}/meshes/base.stl", ExpansionFacts(package_folders=(PACKAGE,)), ["P102"]),
])
def test_a_path_written_out_is_reported(filename: str, facts: ExpansionFacts,
                                        expected: list[str]) -> None:
    assert codes(filename, facts) == expected
