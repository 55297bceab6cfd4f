"""P101/P102 carry their fix as data: the path as package://PACKAGE/PATH of the package that
holds the file, or why not (the file is in no ROS package). One machine's paths in one file
are one finding, whose fix rewrites them all."""

from __future__ import annotations

from pathlib import Path

from robotdesc.cli import main
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


def robot_with(filenames: list[str]):
    links = "".join(f'<link name="l{i}"><visual><geometry><mesh filename="{name}"/></geometry>'
                    f'</visual></link>\n' for i, name in enumerate(filenames))
    return parse_urdf(f'<robot name="arm">\n{links}</robot>'.encode(), "arm.urdf")


def check(code: str, filenames: list[str]) -> list[Finding]:
    rule = get_rule(code)
    return list(rule.check(robot_with(filenames), RuleContext(expansion=ExpansionFacts())))


def make_package(root: Path, name: str = "arm") -> Path:
    (root / name / "meshes").mkdir(parents=True)
    (root / name / "package.xml").write_text(f"<package><name>{name}</name></package>")
    return root / name


def test_one_machines_uris_are_one_finding_whose_fix_rewrites_them_all(tmp_path: Path) -> None:
    # Kinova's generated gen3_2f85.urdf: 37 file:// URIs of one workspace, one problem
    make_package(tmp_path, "arm"), make_package(tmp_path, "gripper")
    names = [f"file://{tmp_path}/arm/meshes/{part}.stl" for part in ("base", "shoulder", "elbow")]
    names.append(f"file://{tmp_path}/gripper/meshes/finger.stl")
    [finding] = check("P102", names)
    assert finding.message == (f"mesh filename '{names[0]}' is a file:// URI, and 3 more mesh "
                               f"references under '{tmp_path}'")
    assert finding.element == "link:l0/visual[0]" and finding.where.span.line == 2
    assert finding.changes == tuple(
        ValueChange(f"link:l{i}/visual[0]/geometry/mesh", "filename", uri) for i, uri in
        enumerate(["package://arm/meshes/base.stl", "package://arm/meshes/shoulder.stl",
                   "package://arm/meshes/elbow.stl", "package://gripper/meshes/finger.stl"]))
    assert finding.fix.splitlines()[3] == \
        "line 5 (link:l3/visual[0]): package://gripper/meshes/finger.stl"


def test_two_machines_paths_are_two_findings() -> None:
    names = ["/home/ana/ws/meshes/a.stl", "/opt/arm/meshes/b.stl", "/home/ana/ws/meshes/c.stl"]
    first, second = check("P101", names)
    assert first.message == ("mesh filename '/home/ana/ws/meshes/a.stl' is an absolute path, "
                             "and 1 more mesh reference under '/home/ana/ws/meshes'")
    assert "is in no ROS package" in first.unfixable and first.changes == ()
    assert second.message == "mesh filename '/opt/arm/meshes/b.stl' is an absolute path"
    # a top folder alone (/opt, /home) is not one machine's path
    assert len(check("P101", ["/opt/a/x.stl", "/opt/b/y.stl"])) == 2


def test_a_single_reference_reads_as_before() -> None:
    [finding] = check("P102", ["file:///opt/arm/meshes/base.stl"])
    assert finding.message == "mesh filename 'file:///opt/arm/meshes/base.stl' is a file:// URI"
    assert finding.fix is None


def test_an_install_space_path_is_fixed_through_its_package() -> None:
    # the machine that wrote the file had the package installed there; ROS resolves
    # package://kortex_description/ to exactly that folder
    for uri, fixed in [
            ("file:///root/ws/install/kortex_description/share/kortex_description/meshes/a.dae",
             "package://kortex_description/meshes/a.dae"),
            ("file:///root/ws/install/share/robotiq_description/meshes/b.dae",
             "package://robotiq_description/meshes/b.dae"),
            ("file:///opt/ros/humble/share/realsense2_description/meshes/d415.stl",
             "package://realsense2_description/meshes/d415.stl")]:
        [finding] = check("P102", [uri])
        assert [c.value for c in finding.changes] == [fixed]
    [alone] = check("P101", ["/usr/share/fonts/meshes/a.stl"])  # not an install space
    assert alone.changes == () and alone.unfixable


def test_lint_fix_rewrites_every_grouped_uri_in_one_run(tmp_path: Path, capsys,
                                                        monkeypatch) -> None:
    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", str(tmp_path / "cache"))
    package = make_package(tmp_path / "ws", "arm")
    (package / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="3"><name>arm</name><version>0.0.0</version>'
        '<description>x</description><maintainer email="a@b.c">a</maintainer>'
        '<license>MIT</license></package>\n')
    for part in ("base", "upper", "fore"):
        (package / "meshes" / f"{part}.stl").write_text("solid x\nendsolid x\n")
    (package / "urdf").mkdir()
    urdf = package / "urdf" / "arm.urdf"
    urdf.write_text("".join(
        ['<?xml version="1.0"?>\n<robot name="arm">\n'] +
        [f'  <link name="{p}"><visual><geometry><mesh filename="file://{package}/meshes/{p}.stl"/>'
         f'</geometry></visual></link>\n' for p in ("base", "upper", "fore")] + ["</robot>\n"]))
    before = urdf.read_text()
    assert main(["lint", str(urdf), "--select", "P102", "--diff"]) == 1
    diff = capsys.readouterr().out
    assert diff.count("\n+  <link") == 3 and urdf.read_text() == before
    main(["lint", str(urdf), "--select", "P102", "--fix"])
    after = urdf.read_text()
    assert "file://" not in after and after.count('filename="package://arm/meshes/') == 3
    assert main(["lint", str(urdf), "--select", "P102"]) == 0
