"""Where things come from: a file position, and the macro calls that led to it."""

from __future__ import annotations

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
class Provenance:
    """The source of one element of an expanded URDF.

    Attributes:
        span: where the element is written (inside a macro body: the body's line).
        macro_stack: the call sites that produced it, innermost call first; empty when the
            element is not produced by a macro.
    """

    span: Span
    macro_stack: tuple[Span, ...] = ()

    def __str__(self) -> str:
        return str(self.span)


#: Private attribute that carries an element's provenance through xacro expansion.
#: Its value is "FILE:LINE" for the element itself, then ";FILE:LINE" per macro call site,
#: innermost first, where FILE is an index into the expansion's file table. A call site
#: repeated n times in a row (deep recursion) is written once as "FILE:LINE*n".
PROVENANCE_ATTR = "_rd_src"


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


def decode_provenance(value: str, files: tuple[str, ...]) -> Provenance:
    """Decode the private attribute's value against the file table."""
    spans: list[Span] = []
    for part in value.split(";"):
        site, _, repeat = part.partition("*")
        index, _, line = site.partition(":")
        span = Span(files[int(index)], int(line))
        spans.extend([span] * (int(repeat) if repeat else 1))
    return Provenance(spans[0], tuple(spans[1:]))
