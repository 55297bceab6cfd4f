"""The guarded XML parser: every problem an XmlSyntaxError at file:line:col, never a crash."""

from __future__ import annotations

from pathlib import Path

import pytest

from robotdesc.errors import InputError, XmlSyntaxError
from robotdesc.xml_input import XmlOptions, parse_xml, read_xml


@pytest.mark.parametrize("data, line, words", [
    (b"", 1, "Document is empty"),
    (b"<r>\x00</r>", 1, "Char 0x0"),
    (b'<?xml version="1.0" encoding="no-such"?><r/>', 1, "unsupported encoding 'no-such'"),
    (b"<r>" + b"<a>" * 300 + b"</a>" * 300 + b"</r>", 1, "nested deeper than 256"),
    (b"<r>&nope;</r>", 1, "Entity 'nope' not defined"),
    (b"<?xml version='1.0'?>\n<!-- c -->\n<!DOCTYPE r [<!ENTITY a 'b'>]><r/>", 3, "DOCTYPE"),
])
def test_problems_are_syntax_errors_naming_the_file(data: bytes, line: int, words: str) -> None:
    with pytest.raises(XmlSyntaxError) as caught:
        parse_xml(data, "/x/in.xml")
    assert caught.value.span.path == "/x/in.xml" and caught.value.span.line == line
    assert words in caught.value.message and "<string>" not in str(caught.value)
    assert "XML_PARSE_HUGE" not in caught.value.message


def test_the_document_kind_is_named_for_a_doctype() -> None:
    with pytest.raises(XmlSyntaxError, match="in a COLLADA file"):
        parse_xml(b"<!DOCTYPE c><c/>", "m.dae", XmlOptions(what="COLLADA file"))


def test_read_xml_names_unreadable_and_oversized_files(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="cannot read"):
        read_xml(tmp_path / "missing.xml")
    (tmp_path / "big.xml").write_bytes(b"<r>" + b" " * 100 + b"</r>")
    with pytest.raises(InputError, match="larger than 50 bytes"):
        read_xml(tmp_path / "big.xml", XmlOptions(what="package.xml"), max_bytes=50)
    (tmp_path / "ok.xml").write_bytes(b"<package><name> p </name></package>")
    assert read_xml(tmp_path / "ok.xml").findtext("name") == " p "


def test_an_undeclared_prefix_is_kept_as_written_with_a_warning(caplog):
    """xacro writes `<xacro:element xacro:name="a:b"/>` as `<a:b/>`: well-formed XML 1.0,
    only not namespace-well-formed; URDF readers take the name as is (issue 28)."""
    root = parse_xml(b'<robot name="r"><link name="l"/><a:b x:y="1"/></robot>', "r.urdf")
    assert [child.tag for child in root] == ["link", "a:b"]
    assert "Namespace prefix" in caplog.text


def test_undeclared_prefixes_do_not_excuse_other_faults():
    with pytest.raises(XmlSyntaxError):
        parse_xml(b'<robot name="r"><a:b></robot>', "r.urdf")
