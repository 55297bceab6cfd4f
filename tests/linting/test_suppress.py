"""Inline suppression comments: parsing, coverage (same line / next line / call sites)."""

from __future__ import annotations

from pathlib import Path

from robotdesc.diagnostics import Diagnostic, Severity
from robotdesc.linting.suppress import apply_suppressions, scan_files, scan_text, unused_codes
from robotdesc.source import Provenance, Span

SOURCE = b"""<robot name="r">
  <!-- robotdesc: ignore J101, mimic-target-missing; reason here -->
  <joint name="a"/>
  <joint name="b"/> <!-- robotdesc: ignore j102 -->
  <!-- an ordinary comment: robotdesc is great -->
  <!--
    robotdesc: ignore S001
  -->
  <link name="x"/>
  <!-- robotdesc: ignore -->
</robot>
"""


def diag(code: str, name: str, path: str, line: int,
         stack: tuple[Span, ...] = ()) -> Diagnostic:
    return Diagnostic(code, name, Severity.ERROR, "msg", Provenance(Span(path, line), stack))


def test_scan_text_finds_directives_with_lines_and_columns(tmp_path: Path) -> None:
    path = str(tmp_path / "r.urdf")
    found = scan_text(SOURCE, path)
    assert [(s.line, s.end_line, s.col, s.codes) for s in found] == [
        (2, 2, 3, ("J101", "mimic-target-missing")),
        (4, 4, 21, ("J102",)),
        (6, 8, 3, ("S001",)),
        (10, 10, 3, ()),
    ]
    assert all(s.path == path for s in found)


def test_scan_files_skips_unreadable_files(tmp_path: Path) -> None:
    path = tmp_path / "r.urdf"
    path.write_bytes(SOURCE)
    assert len(scan_files([str(path), str(tmp_path / "missing.xacro"), str(path)])) == 4


def test_comment_covers_its_line_and_the_next(tmp_path: Path) -> None:
    path = str(tmp_path / "r.urdf")
    suppressions = scan_text(SOURCE, path)
    diagnostics = [
        diag("J101", "revolute-without-limit", path, 3),      # line after the comment
        diag("J201", "mimic-target-missing", path, 2),        # by name, on the comment line
        diag("J102", "x", path, 4),                           # same line, trailing comment
        diag("S001", "no-root-link", path, 9),                # after a multi-line comment
        diag("J101", "revolute-without-limit", path, 4),      # two lines after: kept
        diag("J103", "other", path, 3),                       # code not named: kept
        diag("J101", "revolute-without-limit", path + "x", 3),  # another file: kept
    ]
    outcome = apply_suppressions(diagnostics, suppressions)
    assert [d.code for d in outcome.suppressed] == ["J101", "J201", "J102", "S001"]
    assert [(d.code, d.where.span.line) for d in outcome.kept] == [
        ("J101", 4), ("J103", 3), ("J101", 3)]
    assert unused_codes(suppressions, outcome.used) == []


def test_unused_codes_are_listed(tmp_path: Path) -> None:
    path = str(tmp_path / "r.urdf")
    suppressions = scan_text(SOURCE, path)
    outcome = apply_suppressions([diag("J101", "revolute-without-limit", path, 3)],
                                 suppressions)
    assert [(s.line, code) for s, code in unused_codes(suppressions, outcome.used)] == [
        (2, "mimic-target-missing"), (4, "J102"), (6, "S001")]


def test_call_site_comment_suppresses_one_macro_instance(tmp_path: Path) -> None:
    macro = str(tmp_path / "macro.xacro")
    top = tmp_path / "robot.urdf.xacro"
    top.write_bytes(b"<robot>\n<!-- robotdesc: ignore J101 -->\n<xacro:arm/>\n<xacro:arm/>\n")
    suppressions = scan_files([str(top)])
    first = diag("J101", "n", macro, 7, (Span(str(top), 3),))
    second = diag("J101", "n", macro, 7, (Span(str(top), 4),))
    outcome = apply_suppressions([first, second], suppressions)
    assert outcome.suppressed == (first,)
    assert outcome.kept == (second,)
