"""One verdict everywhere (issue 29): a link whose inertia finding lint suppresses (inline
comment, per-file ignore, baseline) gets no replacement block from `inertia --suggest` or
`--write`, and the inertia table (text, JSON, HTML, `robotdesc.mesh_inertia`) shows it as
suppressed, as `lint` says it is clean."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from mesh.builders import box_triangles, write_binary_stl

import robotdesc
from robotdesc.cli import main
from robotdesc.diagnostics import Diagnostic, Severity
from robotdesc.linting.verdict import suppressed_links
from robotdesc.report.html import inertia_rows_html

#: An arm link whose tensor is far too large for its 0.1 x 0.2 x 0.4 m box (I204), on
#: purpose: the reason is written in the suppression, as the Engineer's wheels do.
URDF = """<?xml version="1.0"?>
<robot name="r">
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base"><inertial><mass value="5"/>
    <inertia ixx="0.05" ixy="0" ixz="0" iyy="0.05" iyz="0" izz="0.05"/></inertial></link>
  <link name="arm">
    <inertial>
      <mass value="1"/>
      {comment}<inertia ixx="16.6667" ixy="0" ixz="0" iyy="14.1667" iyz="0" izz="4.16667"/>
    </inertial>
    <collision><geometry><mesh filename="package://pkg/meshes/box.stl"/></geometry></collision>
  </link>
  <joint name="j" type="continuous"><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit effort="1" velocity="1"/></joint>
</robot>
"""
REASON = "<!-- robotdesc: ignore I204; reflected inertia of the drive, measured -->"


def _package(tmp_path: Path, comment: str) -> Path:
    package = tmp_path / "pkg"
    (package / "meshes").mkdir(parents=True, exist_ok=True)
    (package / "package.xml").write_text("<package format='3'><name>pkg</name></package>")
    write_binary_stl(package / "meshes" / "box.stl", box_triangles((0.1, 0.2, 0.4)))
    path = package / "robot.urdf"
    path.write_text(URDF.format(comment=comment))
    return path


@pytest.fixture
def suppressed(tmp_path: Path) -> Path:
    return _package(tmp_path, REASON)


def test_lint_is_clean_and_inertia_suggests_nothing_for_the_same_link(suppressed: Path,
                                                                      capsys) -> None:
    assert main(["lint", str(suppressed)]) == 0
    capsys.readouterr()
    assert main(["inertia", str(suppressed), "--suggest"]) == 0
    out, err = capsys.readouterr()
    assert "<inertial>" not in out
    assert "1 links left as they are: lint's I204 findings on them are suppressed" in err
    assert main(["inertia", str(suppressed), "--suggest", "--all"]) == 0
    assert "link 'arm'" in capsys.readouterr().out


def test_write_patches_nothing_for_a_suppressed_link(suppressed: Path, tmp_path: Path,
                                                     capsys) -> None:
    patch = tmp_path / "fix.patch"
    assert main(["inertia", str(suppressed), "--write", str(patch)]) == 0
    assert patch.read_text() == ""
    assert "(0 blocks)" in capsys.readouterr().err


def test_tables_show_the_link_as_suppressed(suppressed: Path, capsys) -> None:
    assert main(["inertia", str(suppressed)]) == 0
    assert "suppressed in lint (I204)" in capsys.readouterr().out
    assert main(["inertia", str(suppressed), "--format", "json"]) == 0
    rows = json.loads(capsys.readouterr().out)["links"]
    assert [row["suppressed"] for row in rows if row["link"] == "arm"] == [["I204"]]
    table = robotdesc.mesh_inertia(str(suppressed))
    row = table.row("arm")
    assert row is not None and row.suppressed == ("I204",)
    page = inertia_rows_html(table.rows)
    assert "(suppressed: I204)" in page and 'class="bad"' not in page


def test_a_baseline_counts_as_a_suppression(tmp_path: Path, capsys) -> None:
    path = _package(tmp_path, "")
    baseline = tmp_path / "baseline.json"
    assert main(["lint", str(path), "--write-baseline", str(baseline)]) == 0
    capsys.readouterr()
    assert main(["inertia", str(path), "--suggest"]) == 0
    assert "link 'arm'" in capsys.readouterr().out  # not suppressed without the baseline
    assert main(["inertia", str(path), "--suggest", "--baseline", str(baseline)]) == 0
    out, err = capsys.readouterr()
    assert "<inertial>" not in out and "suppressed" in err


def _diagnostic(code: str, link: str) -> Diagnostic:
    return Diagnostic(code=code, name=code.lower(), severity=Severity.WARNING, message="m",
                      where=None, element=f"link:{link}/inertial", fix=None, target="t")


def test_a_kept_default_on_inertia_finding_overrules_a_suppression() -> None:
    hidden = [_diagnostic("I204", "wheel"), _diagnostic("I204", "head")]
    kept = [_diagnostic("I103", "head"), _diagnostic("G101", "wheel")]
    assert suppressed_links(hidden, kept) == {"wheel": ("I204",)}
