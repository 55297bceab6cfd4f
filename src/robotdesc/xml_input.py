"""The one guarded XML parser: every XML robotdesc reads goes through `parse_xml`.

Descriptions, included files, package.xml, COLLADA meshes and configs are parsed strictly
(no recovery), without entity expansion, DTD loading or network access. Whatever is wrong with
the bytes becomes an `XmlSyntaxError` (an `InputError`, exit code 2) at file:line:col:

- malformed markup (an unterminated comment or tag, `--` in a comment, a redefined attribute,
  a missing attribute value, an undefined entity);
- encodings: invalid bytes for the declared encoding, an encoding libxml2 does not support;
- a DOCTYPE (refused before libxml2 reads it: no billion laughs, no external entities);
- the limits: elements nested deeper than `MAX_DEPTH` (libxml2's own limit, 256 levels, kept
  on purpose: no robot description comes near it) and one text node or attribute value
  longer than `MAX_TEXT_BYTES` (libxml2's limit without its "huge" option).

The tree is walked by lxml's iterators, never by Python recursion, so no input depth can
raise a `RecursionError`.
"""

from __future__ import annotations

import functools
import logging
import os
import re
from dataclasses import dataclass

from lxml import etree

from robotdesc.errors import InputError, XmlSyntaxError
from robotdesc.source import Span

#: Deepest element nesting accepted (libxml2's limit without XML_PARSE_HUGE).
MAX_DEPTH = 256
#: Longest single text node or attribute value accepted, in bytes (libxml2's limit).
MAX_TEXT_BYTES = 10_000_000
#: Largest XML file read by `read_xml` (bytes).
MAX_XML_FILE_BYTES = 256 * 1024 * 1024

_POSITION_SUFFIX = re.compile(r"(?:,? line \d+, column \d+)?(?: \(<string>, line \d+\))?$")
_WHITESPACE = re.compile(rb"[ \t\r\n]*")
_MARKUP_OR_TAG = re.compile(
    r"<!--.*?-->|<!\[CDATA\[.*?\]\]>|<\?.*?\?>|<![^>]*>|</|<", re.DOTALL)
_DOCTYPE_MESSAGE = "a DOCTYPE is not allowed (entities and DTDs are refused)"


@dataclass(frozen=True)
class XmlOptions:
    """How one document is parsed.

    Attributes:
        remove_comments: drop comments from the tree.
        remove_pis: drop processing instructions from the tree.
        remove_blank_text: drop whitespace-only text between elements.
        what: what the document is, in messages ("robot description", "package.xml", ...).
    """

    remove_comments: bool = True
    remove_pis: bool = True
    remove_blank_text: bool = False
    what: str = "XML"


log = logging.getLogger(__name__)

DEFAULT_OPTIONS = XmlOptions()


def parse_xml(data: bytes, path: str, options: XmlOptions = DEFAULT_OPTIONS) -> etree._Element:
    """Parse a whole document strictly; returns its root element.

    Args:
        data: the document's bytes (its encoding from the BOM or XML declaration, else UTF-8).
        path: the file it came from, named in errors.
        options: what to keep and how to name the document.

    Raises:
        XmlSyntaxError: the document is malformed, declares a DOCTYPE or hits a limit.
    """
    if isinstance(data, str):
        data = data.encode("utf-8")
    doctype_at = doctype_offset(data)
    if doctype_at >= 0:
        line = data.count(b"\n", 0, doctype_at) + 1
        raise XmlSyntaxError(f"{_DOCTYPE_MESSAGE} in {_article(options.what)}", Span(path, line))
    parser = etree.XMLParser(resolve_entities=False, no_network=True, recover=False,
                             load_dtd=False, dtd_validation=False, huge_tree=False,
                             remove_comments=options.remove_comments,
                             remove_pis=options.remove_pis,
                             remove_blank_text=options.remove_blank_text)
    try:
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError as error:
        if _only_undeclared_prefixes(parser.error_log):
            return _with_undeclared_prefixes(data, path, options)
        line, col = error.position if error.position else (error.lineno or 0, 0)
        raise XmlSyntaxError(describe_syntax_error(error.msg or str(error)),
                             Span(path, max(line or 0, 0), max(col or 0, 0))) from None
    except (ValueError, LookupError, UnicodeError) as error:  # lxml's own refusals
        raise XmlSyntaxError(f"malformed XML: {error}", Span(path)) from None
    if root is None:
        raise XmlSyntaxError("malformed XML: the document is empty", Span(path))
    if root.getroottree().docinfo.doctype:
        raise XmlSyntaxError(f"{_DOCTYPE_MESSAGE} in {_article(options.what)}", Span(path, 1))
    return root


#: libxml2's "Namespace prefix a on b is not defined" (domain NAMESPACE).
_UNDEFINED_PREFIX = 201


@functools.lru_cache(maxsize=8)
def shared_root(data: bytes) -> etree._Element | None:
    """A document the model's parse accepted, parsed once more and shared (comments and
    processing instructions removed; no entities, DTD or network) by the rules and readers
    that judge its raw elements (S201/S202, the R1xx wiring rules, the controllers file a
    description names): one parse per document instead of one per reader. Read-only: no
    caller may change the tree. None when it cannot be parsed (reported by the model's
    parse).
    """
    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                             huge_tree=False, remove_comments=True, remove_pis=True)
    try:
        return etree.fromstring(data, parser)
    except (etree.XMLSyntaxError, ValueError):
        return None


def _only_undeclared_prefixes(errors: etree._ListErrorLog) -> bool:
    """True when every error is a prefix used without a declaration: the document is
    well-formed XML 1.0, only not namespace-well-formed (xacro writes
    `<xacro:element xacro:name="a:b"/>` as `<a:b/>`, and URDF readers take the name as is)."""
    return len(errors) > 0 and all(e.type == _UNDEFINED_PREFIX for e in errors)


def _with_undeclared_prefixes(data: bytes, path: str, options: XmlOptions) -> etree._Element:
    """The document whose only fault is undeclared prefixes, names kept as written."""
    parser = etree.XMLParser(resolve_entities=False, no_network=True, recover=True,
                             load_dtd=False, dtd_validation=False, huge_tree=False,
                             remove_comments=options.remove_comments,
                             remove_pis=options.remove_pis,
                             remove_blank_text=options.remove_blank_text)
    root = etree.fromstring(data, parser)
    if root is None or not _only_undeclared_prefixes(parser.error_log):
        raise XmlSyntaxError("malformed XML", Span(path))
    log.warning("%s: %s (kept as written, as xacro and URDF readers do)", path,
                parser.error_log[0].message)
    return root


def read_xml(path: str | os.PathLike[str], options: XmlOptions = DEFAULT_OPTIONS,
             max_bytes: int = MAX_XML_FILE_BYTES) -> etree._Element:
    """Read and parse one XML file (see `parse_xml`).

    Raises:
        InputError: the file cannot be read or is larger than `max_bytes`.
        XmlSyntaxError: as `parse_xml`.
    """
    name = os.fspath(path)
    try:
        with open(name, "rb") as handle:
            data = handle.read(max_bytes + 1)
    except OSError as error:
        raise InputError(f"cannot read: {error.strerror or error}", Span(name)) from None
    if len(data) > max_bytes:
        raise InputError(f"{options.what} larger than {max_bytes} bytes", Span(name))
    return parse_xml(data, name, options)


def describe_syntax_error(message: str) -> str:
    """libxml2's message in a user's words, without its position suffix and option hints."""
    text = _POSITION_SUFFIX.sub("", " ".join(message.split()))
    if "Excessive depth in document" in text:
        return (f"elements nested deeper than {MAX_DEPTH} levels (the limit for XML input; "
                "a robot description needs far fewer)")
    if "Buffer size limit exceeded" in text or "Resource limit exceeded" in text:
        return (f"a text or attribute value longer than {MAX_TEXT_BYTES} bytes "
                "(the limit for XML input)")
    if text.startswith("Unsupported encoding"):
        name = text.partition(":")[2].strip()
        return (f"unsupported encoding '{name}' in the XML declaration "
                "(use UTF-8)" if name else "unsupported encoding (use UTF-8)")
    if "Invalid bytes in character encoding" in text or "Input is not proper UTF-8" in text:
        return "malformed XML: bytes that are not valid in the declared encoding (UTF-8 unless declared)"
    text = re.sub(r",? ?use XML_PARSE_HUGE option|,? ?try XML_PARSE_HUGE", "", text)
    text = re.sub(r" line \d+$", "", text).strip(" ,")
    return f"malformed XML: {text or 'not well-formed'}"


def doctype_offset(data: bytes) -> int:
    """Offset of a DOCTYPE in the prolog, or -1 (linear time).

    A DOCTYPE may only follow an optional BOM, the XML declaration, comments, processing
    instructions and whitespace.
    """
    at = 3 if data.startswith(b"\xef\xbb\xbf") else 0
    size = len(data)
    while at < size:
        blank = _WHITESPACE.match(data, at)
        assert blank is not None  # `*`: it matches the empty string
        at = blank.end()
        if data.startswith(b"<?", at):
            end = data.find(b"?>", at + 2)
            at = size if end < 0 else end + 2
        elif data.startswith(b"<!--", at):
            end = data.find(b"-->", at + 4)
            at = size if end < 0 else end + 3
        elif data.startswith(b"<!DOCTYPE", at):
            return at
        else:
            return -1
    return -1


def start_tag_positions(data: bytes, root: etree._Element) -> dict[etree._Element, tuple[int, int]]:
    """Where each element's start tag opens: {element: (line, column)}, both 1-based.

    libxml2's `sourceline` is the line a start tag *ends* on; this scans the document (which
    `parse_xml` accepted, so every `<` outside comments, CDATA and processing instructions
    opens a tag) and pairs the n-th start tag with the n-th element in document order.
    Columns count characters. Empty when the document cannot be decoded or the counts differ.
    """
    text = _decoded(data, root)
    if text is None:
        return {}
    elements = [e for e in root.getroottree().iter() if isinstance(e.tag, str)]
    positions: list[int] = []
    for match in _MARKUP_OR_TAG.finditer(text):
        if match.group(0) == "<":
            positions.append(match.start())
    if len(positions) != len(elements):
        return {}
    found: dict[etree._Element, tuple[int, int]] = {}
    line, line_start, scanned = 1, 0, 0
    for element, offset in zip(elements, positions):
        newlines = text.count("\n", scanned, offset)
        if newlines:
            line += newlines
            line_start = text.rfind("\n", scanned, offset) + 1
        scanned = offset
        found[element] = (line, offset - line_start + 1)
    return found


def _decoded(data: bytes, root: etree._Element) -> str | None:
    encoding = root.getroottree().docinfo.encoding or "utf-8"
    try:
        text = data.decode(encoding)
    except (LookupError, UnicodeError):
        return None
    return text[1:] if text.startswith("\ufeff") else text


def _article(what: str) -> str:
    return what if what in ("XML", "package.xml") else f"a {what}"
