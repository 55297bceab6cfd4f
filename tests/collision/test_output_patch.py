"""The xacro patch of `robotdesc collision`: applied to a copy of the package with `git apply`
or `patch -p1`, the re-expanded robot uses the generated meshes; shared macros are left out;
the element-extent scanner agrees with expat."""

from __future__ import annotations

import re
import shutil
import subprocess
import xml.parsers.expat
from pathlib import Path

import pytest

import robotdesc
from collision.conftest import write_urdf
from robotdesc.cli import main
from robotdesc.collision.xml_extent import element_extents
from robotdesc.errors import XmlSyntaxError

ROBOT = """<?xml version="1.0"?>
<!-- a <collision> in a comment is no element -->
<robot name="demo" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find demo)/urdf/parts.xacro"/>
  <link name="base">
    <visual><geometry><mesh filename="package://demo/meshes/hip.stl"/></geometry></visual>
    <collision>
      <geometry><box size="1 1 1"/></geometry>
    </collision>
    <collision name="second"><geometry><box size="1 1 1"/></geometry></collision>
  </link>
  <link name="bare">
    <visual><geometry><box size="0.1 0.2 0.3"/></geometry></visual>
  </link>
  <xacro:arm/>
  <xacro:leg side="l"/>
  <xacro:leg side="r"/>
  <joint name="j1" type="fixed"><parent link="base"/><child link="bare"/></joint>
  <joint name="j2" type="fixed"><parent link="base"/><child link="arm"/></joint>
  <joint name="j3" type="fixed"><parent link="base"/><child link="l_leg"/></joint>
  <joint name="j4" type="fixed"><parent link="base"/><child link="r_leg"/></joint>
</robot>
"""

PARTS = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm">
    <link name="arm">
      <visual><geometry><mesh filename="package://demo/meshes/hip.stl"/></geometry></visual>
      <collision><geometry><sphere radius="${0.1 * 2}"/></geometry></collision>
    </link>
  </xacro:macro>
  <xacro:macro name="leg" params="side">
    <link name="${side}_leg">
      <visual><geometry><box size="0.1 0.2 0.3"/></geometry></visual>
      <collision><geometry><sphere radius="0.1"/></geometry></collision>
    </link>
  </xacro:macro>
</robot>
"""

MESH_CODES = {"M101", "M102", "M103", "M104"}


def _snapshot(root: Path, skip: Path | None = None) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*"))
            if p.is_file() and (skip is None or skip not in p.parents)}


def _header(patch: str) -> str:
    """The patch's comment header as one line of text."""
    return " ".join(line[1:].strip() for line in patch.split("\n\n", 1)[0].splitlines())


def _apply_command(patch: str) -> tuple[str, list[str], list[str]]:
    """The root (from the patch's folder) and the two commands the header gives."""
    root = re.search(r"^# Paths are relative to the root folder (\S+) ", patch, re.MULTILINE).group(1)
    git = re.search(r"^# Apply it there:  (git apply \S+)$", patch, re.MULTILINE).group(1).split()
    gnu = re.search(r"^#\s+or:  (patch -p1) < (\S+)$", patch, re.MULTILINE)
    return root, git, gnu.group(1).split() + ["-i", gnu.group(2)]


def _run(command: list[str], cwd: Path) -> None:
    done = subprocess.run(command, cwd=cwd, capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stdout + done.stderr


def _generate(source: Path, out: Path) -> int:
    return main(["collision", str(source), "--method", "hull", "--out", str(out),
                 "--limit-hull-vertices", "5000", "--jobs", "2"])


def test_patch_applied_with_git_gives_the_generated_collisions(package, tmp_path_factory):
    (package / "urdf" / "robot.urdf.xacro").write_text(ROBOT)
    (package / "urdf" / "parts.xacro").write_text(PARTS)
    out = package / "collision"
    before = _snapshot(package)
    assert _generate(package / "urdf" / "robot.urdf.xacro", out) == 0
    assert _snapshot(package, skip=out) == before  # robotdesc changed no source file
    patch = (out / "demo.collision.patch").read_text()
    assert "demo.collision.patch" in (out / "robotdesc-collision.json").read_text()
    assert "# Patched links: base, bare, arm\n" in patch
    header = _header(patch)
    assert "Not patched (paste their macros from demo.collision.xacro by hand; positions " \
        "from this patch's folder): l_leg, r_leg: its <collision> at ../urdf/parts.xacro:11 " \
        "makes 2 links (a macro called more than once" in header
    assert "xacro arguments; positions from this patch's folder): arm " \
        "(../urdf/parts.xacro:5)" in header  # the expression it replaced is named
    snippet = (out / "demo.collision.xacro").read_text()
    assert "not in demo.collision.patch" in snippet.split("l_leg_collision")[0]

    root, git, _ = _apply_command(patch)
    assert root == ".."
    copy = tmp_path_factory.mktemp("applied") / "demo"
    shutil.copytree(package, copy)
    shutil.rmtree(package)  # the copy alone must resolve
    _run(git, cwd=(copy / "collision" / root).resolve())
    robot = robotdesc.load(str(copy / "urdf" / "robot.urdf.xacro"))
    for link in ("base", "bare", "arm"):
        [collision] = robot.link(link).collisions
        assert collision.geometry.filename == f"package://demo/collision/meshes/{link}.stl"
    for link in ("l_leg", "r_leg"):
        assert type(robot.link(link).collisions[0].geometry).__name__ == "Sphere"
    lint = robotdesc.lint(str(copy / "urdf" / "robot.urdf.xacro"))
    assert not [d for d in lint.diagnostics if d.code in MESH_CODES]
    text = (copy / "urdf" / "robot.urdf.xacro").read_text()
    assert '    <collision name="bare_collision_0">\n      <origin' in text  # indented


def test_relative_paths_crlf_and_patch_p1(tmp_path, tmp_path_factory):
    from collision.conftest import HIP, real_mesh

    folder = tmp_path / "ws" / "robot"  # no package.xml: mesh paths stay relative
    folder.mkdir(parents=True)
    shutil.copy(real_mesh(HIP), folder / "hip.stl")
    parts = PARTS.replace("package://demo/meshes/hip.stl", "hip.stl")
    robot = ROBOT.replace("package://demo/meshes/hip.stl", "hip.stl") \
        .replace("$(find demo)/urdf/parts.xacro", "parts.xacro")
    robot = robot.replace("  <link name=\"bare\">", "  <link name=\"late\">\n"
                          "    <visual><geometry><mesh filename=\"hip.stl\"/></geometry>"
                          "</visual></link>\n  <link name=\"bare\">")
    robot = robot.replace("</joint>\n</robot>\n",
                          "</joint>\n<joint name=\"j5\" type=\"fixed\"><parent link=\"base\"/>"
                          "<child link=\"late\"/></joint>\n  <link name=\"tail\">"
                          "<visual><geometry><mesh filename=\"hip.stl\"/></geometry></visual>"
                          "</link><joint name=\"j6\" type=\"fixed\"><parent link=\"base\"/>"
                          "<child link=\"tail\"/></joint></robot>")
    (folder / "robot.urdf.xacro").write_bytes(robot.replace("\n", "\r\n").encode())
    (folder / "parts.xacro").write_bytes(parts.replace("\n", "\r\n").encode())
    out = tmp_path / "ws" / "out"
    assert _generate(folder / "robot.urdf.xacro", out) == 0
    patch = (out / "demo.collision.patch").read_text()
    assert "No newline at end of file" in patch  # `tail` sits on the unterminated last line
    root, git, gnu = _apply_command(patch)
    assert root == "../robot"

    for tool in (gnu, git):
        if shutil.which(tool[0]) is None:
            continue
        copy = tmp_path_factory.mktemp("applied") / "ws"
        shutil.copytree(tmp_path / "ws", copy)
        if tool is git:  # a root below the top of a git work tree
            _run(["git", "init", "-q", "."], cwd=copy)
        _run(tool, cwd=(copy / "out" / root).resolve())
        patched = copy / "robot" / "robot.urdf.xacro"
        data = patched.read_bytes()
        assert data.count(b"\n") == data.count(b"\r\n")  # still CRLF throughout
        loaded = robotdesc.load(str(patched))
        for link in ("base", "bare", "late", "tail", "arm"):
            [collision] = loaded.link(link).collisions
            assert collision.geometry.filename == f"../out/meshes/{link}.stl"
        lint = robotdesc.lint(str(patched))
        assert not [d for d in lint.diagnostics if d.code in MESH_CODES]


def test_collisions_from_a_generated_snippet_are_not_patched(package):
    """A link that already calls the generated macro: the run rewrites the snippet itself."""
    top = package / "urdf" / "robot.urdf.xacro"
    link = ('<link name="base"><visual><geometry><mesh filename="package://demo/meshes/'
            'hip.stl"/></geometry></visual>{}</link>')
    head = '<?xml version="1.0"?>\n<robot name="demo" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
    top.write_text(head + link.format("<collision><geometry><box size='1 1 1'/></geometry>"
                                      "</collision>") + "\n</robot>\n")
    out = package / "collision"
    assert _generate(top, out) == 0
    top.write_text(head + '<xacro:include filename="$(find demo)/collision/demo.collision.xacro"/>\n'
                   + link.format("<xacro:base_collision/>") + "\n</robot>\n")
    assert _generate(top, out) == 0
    patch = (out / "demo.collision.patch").read_text()
    assert "# Nothing to patch" in patch and "\n--- a/" not in patch
    assert "Up to date (they call this run's macros already, nothing to do): base" \
        in _header(patch)
    assert "Not patched" not in _header(patch)
    assert "not in demo.collision.patch: up to date: its <collision> comes from " \
        "demo.collision.xacro:" in (out / "demo.collision.xacro").read_text()


def test_no_patch_for_a_plain_urdf(package):
    urdf = write_urdf(package, {"hip": "hip.stl"})
    assert _generate(urdf, package / "collision") == 0
    assert not list((package / "collision").glob("*.patch"))


# --- the element-extent scanner -----------------------------------------------------------

SAMPLE = ('<?xml version="1.0"?>\r\n<!-- <collision> <link name="x"> -->\r\n'
          '<robot a="x > y" b=\'/>\'>\r\n'
          '  <link name="a"><collision/>\r\n'
          '    <collision name="n"><geometry><![CDATA[<collision>]]></geometry>\r\n'
          '    </collision><?pi <collision>?>\r\n'
          '  </link>\r\n'
          '  <a><a/><a>\r\n</a></a>\r\n'
          '</robot>')


def _expat_lines(text: str) -> list[tuple[str, int]]:
    parser = xml.parsers.expat.ParserCreate()
    seen = []
    parser.StartElementHandler = lambda name, _attrs: seen.append(
        (name, parser.CurrentLineNumber))
    parser.Parse(text.encode(), True)
    return seen


def test_element_extents_match_expat_lines_and_the_text():
    extents = element_extents(SAMPLE)
    assert [(e.name, e.line) for e in extents] == _expat_lines(SAMPLE)
    robot, link, empty, named, geometry, outer, inner, third = extents
    assert SAMPLE[named.start:named.end] == (
        '<collision name="n"><geometry><![CDATA[<collision>]]></geometry>\r\n    </collision>')
    assert empty.self_closing and SAMPLE[empty.start:empty.end] == "<collision/>"
    assert not named.self_closing and named.parent == 1 and geometry.parent == 3
    assert SAMPLE[outer.start:outer.end] == "<a><a/><a>\r\n</a></a>"
    assert (inner.parent, third.parent) == (5, 5) and third.line == 8
    assert SAMPLE[link.content_end:link.end] == "</link>"
    assert SAMPLE[robot.start:robot.end].endswith("</robot>") and robot.parent == -1


def test_element_extents_counts_cr_and_lf_line_breaks_as_expat_does():
    text = "<r>\r<a/>\n<b/>\r\n\r\n<c\n x='1'/></r>"
    assert [(e.name, e.line) for e in element_extents(text)] == _expat_lines(text)


@pytest.mark.parametrize("text", ["<a><b></a>", "<a>", "<a x='>", "<a></b>", "<!-- open",
                                  "</a>"])
def test_element_extents_refuse_what_they_cannot_pair(text):
    with pytest.raises(XmlSyntaxError):
        element_extents(text)
