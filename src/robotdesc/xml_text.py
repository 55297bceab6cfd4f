"""Text and attribute values escaped for the XML robotdesc writes (URDF, SRDF, fixes).

The standard library's `xml.sax.saxutils` does the same, but importing it costs about 25 ms
(it pulls in `urllib.request`), paid by every command that loads the rule catalog.
"""

from __future__ import annotations

_TEXT = {"&": "&amp;", "<": "&lt;", ">": "&gt;"}
_ATTRIBUTE = {**_TEXT, '"': "&quot;", "\n": "&#10;", "\r": "&#13;", "\t": "&#9;"}
_TEXT_TABLE = str.maketrans(_TEXT)
_ATTRIBUTE_TABLE = str.maketrans(_ATTRIBUTE)


def escape_text(text: str) -> str:
    """`text` as XML character data: `&`, `<` and `>` escaped."""
    return text.translate(_TEXT_TABLE)


def escape_attribute(value: str) -> str:
    """`value` for inside a double-quoted attribute (quotes and whitespace controls escaped,
    so that a parser reads back exactly `value`)."""
    return value.translate(_ATTRIBUTE_TABLE)


def quote_attribute(value: str) -> str:
    """`value` as a double-quoted attribute value, quotes included."""
    return f'"{escape_attribute(value)}"'
