"""Exact locations: start tags that span lines, columns in the model and in every report."""

from __future__ import annotations

import json
from pathlib import Path

from robotdesc.cli import main
from robotdesc.model.parse import parse_urdf
from robotdesc.xml_input import parse_xml, start_tag_positions

MULTILINE = b"""<?xml version="1.0"?>
<!-- a comment with <link> inside -->
<robot
    name="r">
  <link
      name="base"/><link name="second"/>
  <![CDATA[ <joint> ]]>
  <joint name="j"
         type="fixed">
    <parent link="base"/>
    <child
      link="missing"/>
  </joint>
</robot>
"""


def test_start_tag_positions_are_where_tags_open() -> None:
    root = parse_xml(MULTILINE, "m.urdf")
    positions = start_tag_positions(MULTILINE, root)
    assert positions[root] == (3, 1)
    assert [positions[e] for e in root] == [(5, 3), (6, 20), (8, 3)]
    child = root.find("joint/child")
    assert positions[child] == (11, 5) and child.sourceline == 12  # libxml2: where it ends


def test_model_spans_carry_start_line_and_column() -> None:
    robot = parse_urdf(MULTILINE, "m.urdf")
    assert robot.where.span.line == 3 and robot.where.span.col == 1
    assert robot.link("second").where.span.col == 20
    assert robot.joint("j").where.span.line == 8


def test_non_ascii_columns_count_characters() -> None:
    data = '<robot name="é"><link name="ü"/><link name="x"/></robot>'.encode()
    robot = parse_urdf(data, "u.urdf")
    assert [link.where.span.col for link in robot.links] == [17, 33]


def test_utf16_documents_have_positions() -> None:
    data = '<?xml version="1.0" encoding="utf-16"?>\n<robot name="r">\n <link name="a"/>\n</robot>'
    robot = parse_urdf(data.encode("utf-16"), "w.urdf")
    assert robot.links[0].where.span.line == 3 and robot.links[0].where.span.col == 2


def _lint(tmp_path: Path, name: str, text: str, fmt: str, capsys) -> dict:
    path = tmp_path / name
    path.write_text(text)
    out = tmp_path / f"report.{fmt}"
    assert main(["lint", str(path), "--format", fmt, "-o", str(out)]) == 1
    return json.loads(out.read_text())


def test_json_and_sarif_have_columns_for_plain_urdf(tmp_path: Path, capsys) -> None:
    text = MULTILINE.decode()
    report = _lint(tmp_path, "m.urdf", text, "json", capsys)
    found = [d for d in report["diagnostics"] if d["code"] == "S108"]
    assert found and (found[0]["line"], found[0]["column"]) == (8, 3)
    assert all(d["column"] for d in report["diagnostics"] if d["line"])
    sarif = _lint(tmp_path, "m.urdf", text, "sarif", capsys)
    regions = [r["locations"][0]["physicalLocation"]["region"]
               for r in sarif["runs"][0]["results"]]
    assert regions and all(r.get("startColumn") for r in regions if r.get("startLine"))


def test_json_has_columns_for_xacro(tmp_path: Path, capsys) -> None:
    text = ('<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            '  <xacro:macro name="j" params="n">\n'
            '      <joint name="${n}" type="fixed"><parent link="base"/><child link="nope"/>'
            '</joint>\n  </xacro:macro>\n  <link name="base"/>\n  <xacro:j n="a"/>\n</robot>\n')
    report = _lint(tmp_path, "r.urdf.xacro", text, "json", capsys)
    found = [d for d in report["diagnostics"] if d["code"] == "S108"]
    assert found and (found[0]["line"], found[0]["column"]) == (4, 7), found
