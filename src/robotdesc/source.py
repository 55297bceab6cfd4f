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
#: innermost first, where FILE is an index into the expansion's file table.
PROVENANCE_ATTR = "_rd_src"


def encode_provenance(own: tuple[int, int], calls: tuple[tuple[int, int], ...] = ()) -> str:
    """Encode (file index, line) pairs into the private attribute's value."""
    return ";".join(f"{f}:{line}" for f, line in (own, *calls))


def decode_provenance(value: str, files: tuple[str, ...]) -> Provenance:
    """Decode the private attribute's value against the file table."""
    spans = []
    for part in value.split(";"):
        index, _, line = part.partition(":")
        spans.append(Span(files[int(index)], int(line)))
    return Provenance(spans[0], tuple(spans[1:]))
