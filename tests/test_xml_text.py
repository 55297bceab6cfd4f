"""Escaped text and attributes read back exactly, as the standard library's saxutils has them."""

from __future__ import annotations

from xml.sax.saxutils import escape, quoteattr

import pytest
from lxml import etree

from robotdesc.xml_text import escape_text, quote_attribute

SAMPLES = ["plain", "a & b", "<tag>", 'say "hi"', "it's", "tab\there\nnew\rline", "ünïcode →"]


@pytest.mark.parametrize("value", SAMPLES)
def test_an_attribute_reads_back_exactly(value: str) -> None:
    element = etree.fromstring(f"<x a={quote_attribute(value)}/>")
    assert element.get("a") == value
    assert etree.fromstring(f"<x a={quoteattr(value)}/>").get("a") == value


@pytest.mark.parametrize("value", SAMPLES)
def test_text_is_escaped_as_saxutils_does(value: str) -> None:
    assert escape_text(value) == escape(value)
    assert etree.fromstring(f"<x>{escape_text(value)}</x>").text == value.replace("\r", "\n")
