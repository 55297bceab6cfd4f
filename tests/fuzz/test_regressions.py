"""Inputs the fuzzing campaign (and issue 20) found crashing, minimised, one test each.

Each must give exit code 0, 1 or 2, name the file (never `<string>`), say what is wrong, and
print no traceback or internal-error text.
"""

from __future__ import annotations

import json
import struct
from pathlib import Path

import pytest

from fuzz.harness import run_in_process

FIXTURES = Path(__file__).parent / "fixtures"

#: fixture -> (line the error is reported at, words the message must contain)
MALFORMED = {
    "comment_double_hyphen.urdf": (3, "Double hyphen within comment"),
    "invalid_utf8_bytes.urdf": (3, "not valid in the declared encoding"),
    "encoding_ebcdic.urdf": (1, "unsupported encoding 'EBCDIC-US'"),
    "attribute_redefined.urdf": (3, "Attribute name redefined"),
    "comment_unterminated.urdf": (6, "Comment not terminated"),
    "start_tag_unterminated.urdf": (4, "malformed XML"),
    "attribute_value_missing.urdf": (3, "AttValue"),
    "doctype_entity.urdf": (2, "DOCTYPE is not allowed"),
}


def _run(*argv: str) -> tuple[int | None, str]:
    code, text, _ = run_in_process(list(argv), timeout_s=120)
    return code, text


def _clean(text: str) -> None:
    for bad in ("Traceback", "internal error", "This is a bug", "<string>"):
        assert bad not in text, text


@pytest.mark.parametrize("command", ["lint", "expand"])
@pytest.mark.parametrize("name", sorted(MALFORMED))
def test_malformed_xml_is_an_input_error_at_its_line(name: str, command: str,
                                                      tmp_path: Path) -> None:
    line, words = MALFORMED[name]
    path = FIXTURES / name
    argv = [command, str(path)] + (["-o", str(tmp_path / "out.urdf")] if command == "expand"
                                   else [])
    code, text = _run(*argv)
    assert code == 2, text
    _clean(text)
    assert f"{name}:{line}" in text and words in text, text
    assert not (tmp_path / "out.urdf").exists()


@pytest.mark.parametrize("name, line", [("inertia_overflow.urdf", 6), ("rpy_huge.urdf", 5),
                                        ("axis_underflow.urdf", 8), ("mass_nan_inf.urdf", 5)])
def test_extreme_numbers_are_findings_at_their_line(name: str, line: int,
                                                   tmp_path: Path) -> None:
    report_file = tmp_path / "report.json"
    code, text = _run("lint", "--format", "json", "-o", str(report_file), str(FIXTURES / name))
    assert code == 1, text
    _clean(text)
    report = json.loads(report_file.read_text())
    unreadable = [d for d in report["diagnostics"] if d["code"] == "S110"]
    assert any(d["line"] == line and d["column"] for d in unreadable), unreadable
    for command in ("inertia", "info"):
        code, text = _run(command, str(FIXTURES / name))
        assert code in (0, 1, 2), text
        _clean(text)


def test_start_tags_spanning_lines_are_located_where_they_open(tmp_path: Path) -> None:
    report_file = tmp_path / "report.json"
    _run("lint", "--format", "json", "-o", str(report_file),
         str(FIXTURES / "multiline_start_tags.urdf"))
    report = json.loads(report_file.read_text())
    joint = [d for d in report["diagnostics"] if d["code"] == "S108"]
    assert joint and joint[0]["line"] == 6 and joint[0]["column"] == 3, joint


def test_nesting_beyond_the_limit_is_an_input_error(tmp_path: Path) -> None:
    path = tmp_path / "deep.urdf"
    path.write_bytes(b'<robot name="r">' + b"<link>" * 300 + b"</link>" * 300 + b"</robot>")
    for command in ("lint", "expand"):
        code, text = _run(command, str(path))
        assert code == 2 and "deep.urdf:1" in text and "nested deeper than 256" in text, text
        _clean(text)


def test_a_value_beyond_the_parser_buffer_is_an_input_error(tmp_path: Path) -> None:
    path = tmp_path / "huge.urdf"
    path.write_bytes(b'<robot name="' + b"x" * 10_500_000 + b'"><link name="a"/></robot>')
    code, text = _run("lint", str(path))
    assert code == 2 and "huge.urdf:1" in text and "longer than 10000000 bytes" in text, text[:500]
    _clean(text)


def test_a_suppression_naming_a_code_many_times_counts_once(tmp_path: Path) -> None:
    path = tmp_path / "flood.urdf"
    comment = b"<!-- robotdesc: ignore " + b",".join([b"J102"] * 20_000) + b" -->"
    path.write_bytes(b'<robot name="r">\n' + comment + b'\n<link name="a"/>\n</robot>\n')
    code, text, size = run_in_process(["lint", str(path)], timeout_s=60)
    assert code == 1 and size < 20_000, text[:2000]
    assert text.count("unused suppression") == 1
    _clean(text)


def test_distinct_codes_in_one_comment_are_capped_and_lines_clipped(tmp_path: Path) -> None:
    path = tmp_path / "many.urdf"
    codes = b",".join(b"Z%d" % n for n in range(20_000))
    path.write_bytes(b'<robot name="r">\n<!-- robotdesc: ignore ' + codes + b' -->\n'
                     b'<link name="a"/>\n</robot>\n')
    code, text, size = run_in_process(["lint", str(path)], timeout_s=60)
    assert code == 1 and size < 200_000, size
    assert "only the first 100 are read" in text
    _clean(text)


def test_a_config_nested_500_arrays_deep_is_an_input_error(tmp_path: Path) -> None:
    (tmp_path / "robotdesc.toml").write_text("ignore = " + "[" * 500 + "]" * 500 + "\n")
    (tmp_path / "r.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    code, text = _run("lint", str(tmp_path / "r.urdf"))
    assert code == 2 and "robotdesc.toml:1" in text and "nested deeper than" in text, text
    _clean(text)


def _stl(count: int, declared: int | None = None) -> bytes:
    triangle = struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0)
    return b"\0" * 80 + struct.pack("<I", count if declared is None else declared) + \
        triangle * count


BAD_MESHES = {
    "latin1.obj": (b"# mod\xe8le\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", None),
    "noextension": (_stl(4), "has no file extension"),
    "entity.dae": (b'<?xml version="1.0"?>\n<!DOCTYPE c [<!ENTITY x SYSTEM '
                   b'"file:///etc/passwd">]>\n<COLLADA>&x;</COLLADA>\n', "DOCTYPE is not allowed"),
    "zero.dae": (b"", "is empty"),
    "deep.dae": (b"<COLLADA>" + b"<node>" * 3000 + b"</node>" * 3000 + b"</COLLADA>",
                 "nested deeper than 256"),
    "lying.stl": (_stl(4, declared=10**9), None),
    "nan.stl": (_stl(1)[:84 + 12] + struct.pack("<9f", *[float("nan")] * 9) + b"\0\0",
                "non-finite"),
}


@pytest.mark.parametrize("name", sorted(BAD_MESHES))
def test_bad_meshes_are_findings_not_crashes(name: str, tmp_path: Path) -> None:
    data, words = BAD_MESHES[name]
    (tmp_path / name).write_bytes(data)
    (tmp_path / "r.urdf").write_text(
        '<robot name="r"><link name="a"><inertial><mass value="1"/><inertia ixx="1" ixy="0" '
        'ixz="0" iyy="1" iyz="0" izz="1"/></inertial><visual><geometry>'
        f'<mesh filename="{name}"/></geometry></visual></link></robot>\n')
    for command in ("lint", "inertia", "view"):
        extra = ["-o", str(tmp_path / "v.html"), "--no-lint"] if command == "view" else []
        code, text = _run(command, str(tmp_path / "r.urdf"), *extra)
        assert code in (0, 1, 2), text
        _clean(text)
        assert "charset_normalizer" not in text and "format '.'" not in text, text
        if command == "lint" and words:
            assert words in text, text


def test_deep_nesting_made_by_xacro_is_an_input_error_naming_the_source(tmp_path: Path) -> None:
    path = tmp_path / "deep.urdf.xacro"
    path.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                    '<link name="a"/>' + "<x>" * 3000 + "</x>" * 3000 + "</robot>\n")
    for command in ("lint", "expand"):
        code, text = _run(command, str(path), "--no-cache")
        assert code == 2 and "deep.urdf.xacro: error: elements nested deeper than 256" in text, \
            text[:600]
        assert "in the document xacro expanded this file to" in text
        _clean(text)


def test_a_limit_of_negative_zero_is_zero() -> None:
    """Campaign seed 20, mutant 4545 (panda, minimised): K201 sampled uniform(0.0, -0.0)."""
    code, text = _run("lint", "--format", "json", str(FIXTURES / "limit_negative_zero.urdf"))
    assert code in (0, 1), text
    _clean(text)
