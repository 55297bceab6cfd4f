"""Where things come from: a file position, and the macro calls that led to it."""

from __future__ import annotations

import re
from dataclasses import dataclass


@dataclass(frozen=True, order=True)
class Span:
    """A position in a source file.

    Attributes:
        path: file path as given or resolved (absolute for files read by expansion).
        line: 1-based line number; 0 when unknown.
        col: 1-based column; 0 when unknown.
    """

    path: str
    line: int = 0
    col: int = 0

    def __str__(self) -> str:
        if self.line and self.col:
            return f"{self.path}:{self.line}:{self.col}"
        if self.line:
            return f"{self.path}:{self.line}"
        return self.path


@dataclass(frozen=True)
class PassedValue:
    """An attribute of a macro body whose value came in through a macro parameter.

    Attributes:
        element: the tag of the element in the body ("mass" for `<mass value="${m}"/>`).
        attribute: the attribute's name ("value").
        span: the call site where the value was written (through nested macros: the
            outermost call that wrote it as text).
    """

    element: str
    attribute: str
    span: Span

    def __str__(self) -> str:
        return f"{self.element} {self.attribute}"


def passed_sites(passed: tuple[PassedValue, ...]) -> list[tuple[Span, tuple[str, ...]]]:
    """The call sites of passed values, in order, each with the values it wrote."""
    sites: dict[Span, list[str]] = {}
    for value in passed:
        sites.setdefault(value.span, []).append(str(value))
    return [(span, tuple(names)) for span, names in sites.items()]


@dataclass(frozen=True)
class Provenance:
    """The source of one element of an expanded URDF.

    Attributes:
        span: where the element is written (inside a macro body: the body's line).
        macro_stack: the call sites that produced it, innermost call first; empty when the
            element is not produced by a macro.
        passed: the element's attributes whose values a macro call passed in, with the call
            site that wrote each value (shown as "value passed at file:line").
    """

    span: Span
    macro_stack: tuple[Span, ...] = ()
    passed: tuple[PassedValue, ...] = ()

    def __str__(self) -> str:
        return str(self.span)


#: Private attribute that carries an element's provenance through xacro expansion.
#: Its value is "FILE:LINE" for the element itself, then ";FILE:LINE" per macro call site,
#: innermost first, where FILE is an index into the expansion's file table. A call site
#: repeated n times in a row (deep recursion) is written once as "FILE:LINE*n". Then, when
#: a macro parameter gave some of the element's attribute values,
#: "|ATTRIBUTE@FILE:LINE,ATTRIBUTE@FILE:LINE" names the call site that wrote each value.
PROVENANCE_ATTR = "_rd_src"

#: Separates the call chain from the passed values in `PROVENANCE_ATTR`.
PASSED_SEPARATOR = "|"


def compress_chain(sites: list[str]) -> str:
    """Join call sites with ";", writing a run of n identical sites as "site*n"."""
    parts: list[str] = []
    previous, count = None, 0
    for site in sites:
        if site == previous:
            count += 1
            continue
        if previous is not None:
            parts.append(previous if count == 1 else f"{previous}*{count}")
        previous, count = site, 1
    if previous is not None:
        parts.append(previous if count == 1 else f"{previous}*{count}")
    return ";".join(parts)


def encode_passed(values: dict[str, str]) -> str:
    """Encode "TAG.ATTRIBUTE" -> call site ("FILE:LINE") as the attribute's passed part."""
    return ",".join(f"{name}@{site}" for name, site in values.items())


def decode_passed(value: str, files: tuple[str, ...]) -> tuple[PassedValue, ...]:
    """Decode the passed part of `PROVENANCE_ATTR` (after `PASSED_SEPARATOR`)."""
    passed: list[PassedValue] = []
    for item in value.split(","):
        name, _, site = item.rpartition("@")
        element, _, attribute = name.rpartition(".")
        index, _, line = site.partition(":")
        passed.append(PassedValue(element, attribute, Span(files[int(index)], int(line))))
    return tuple(passed)


def decode_provenance(value: str, files: tuple[str, ...]) -> Provenance:
    """Decode the private attribute's value against the file table."""
    value, _, passed = value.partition(PASSED_SEPARATOR)
    spans: list[Span] = []
    for part in value.split(";"):
        site, _, repeat = part.partition("*")
        index, _, line = site.partition(":")
        span = Span(files[int(index)], int(line))
        spans.extend([span] * (int(repeat) if repeat else 1))
    return Provenance(spans[0], tuple(spans[1:]), decode_passed(passed, files) if passed else ())


_PROVENANCE_VALUE = rb"[0-9:;*|@,A-Za-z_.\-]*"
_PROVENANCE_ATTRIBUTE = re.compile(rb"[ \t\r\n]+" + PROVENANCE_ATTR.encode()
                                   + rb'=(?:"' + _PROVENANCE_VALUE + rb'"|\'' + _PROVENANCE_VALUE
                                   + rb"')")

_MARKUP = re.compile(rb"<!--.*?-->|<!\[CDATA\[.*?\]\]>|<\?.*?\?>|<[A-Za-z_:][^>]*>", re.DOTALL)


def strip_provenance(data: bytes) -> bytes:
    """Return the document without the private provenance attribute, otherwise unchanged.

    Only start tags are edited; comments, CDATA, processing instructions and text are
    copied byte for byte.
    """
    marker = PROVENANCE_ATTR.encode()
    if marker not in data:
        return data

    def clean(match: re.Match[bytes]) -> bytes:
        markup: bytes = match.group(0)
        if markup[1:2] in (b"!", b"?") or marker not in markup:
            return markup
        return _PROVENANCE_ATTRIBUTE.sub(b"", markup)

    return _MARKUP.sub(clean, data)
