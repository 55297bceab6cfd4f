"""Inline suppressions: `<!-- robotdesc: ignore CODE[, CODE ...] -->` in a source file.

A comment suppresses a finding of a named rule (its code or its kebab-case name) when the
finding's line is on the comment's line(s) or on the line right after it. A finding made inside
a macro body can be suppressed at the body line (every call) or at one of its call sites (that
call only). Text after a `;` is a free-form reason: `<!-- robotdesc: ignore J101; vendor -->`.
"""

from __future__ import annotations

import functools
import logging
import os
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from robotdesc.diagnostics import Diagnostic

_COMMENT = re.compile(rb"<!--(.*?)-->", re.DOTALL)
_DIRECTIVE = re.compile(r"^\s*robotdesc\s*:\s*ignore\b(.*)$", re.DOTALL | re.IGNORECASE)
_MARKER = b"robotdesc"
#: Distinct rule codes read from one comment (more are ignored with a warning): no rule set
#: has this many, and a comment naming thousands must not make thousands of findings.
MAX_CODES_PER_COMMENT = 100

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class Suppression:
    """One suppression comment.

    Attributes:
        path: the file it is written in (absolute, normalised).
        line: the 1-based line the comment starts on.
        end_line: the line the comment ends on.
        col: the 1-based column of `<!--`.
        codes: the rule codes or names it names, as written (codes upper-cased).
    """

    path: str
    line: int
    end_line: int
    col: int
    codes: tuple[str, ...]

    def covers(self, path: str, line: int) -> bool:
        """Whether a finding at path:line is on the comment or the line after it."""
        return path == self.path and self.line <= line <= self.end_line + 1


@dataclass(frozen=True)
class SuppressionOutcome:
    """The result of applying suppressions.

    Attributes:
        kept: the diagnostics no comment suppresses.
        suppressed: the diagnostics that were suppressed.
        used: (suppression, code as written) pairs that suppressed at least one diagnostic.
    """

    kept: tuple[Diagnostic, ...]
    suppressed: tuple[Diagnostic, ...]
    used: frozenset[tuple[Suppression, str]]


@functools.lru_cache(maxsize=4096)
def normalise_path(path: str) -> str:
    """The form suppressions and diagnostics compare paths in."""
    return os.path.normcase(os.path.abspath(path))


def scan_text(data: bytes, path: str) -> list[Suppression]:
    """Find the suppression comments in one file's bytes (UTF-8; bad bytes are replaced).

    A code named twice in one comment counts once; at most MAX_CODES_PER_COMMENT are read.
    """
    if _MARKER not in data:
        return []
    found = []
    where = normalise_path(path)
    for match in _COMMENT.finditer(data):
        body = match.group(1).decode("utf-8", errors="replace")
        directive = _DIRECTIVE.match(body)
        if not directive:
            continue
        selectors = directive.group(1).split(";", 1)[0]
        codes = tuple(dict.fromkeys(_normalise_code(token)
                                    for token in re.split(r"[,\s]+", selectors) if token))
        start = match.start()
        line = data.count(b"\n", 0, start) + 1
        if len(codes) > MAX_CODES_PER_COMMENT:
            log.warning("%s:%d: the suppression comment names %d rules; only the first %d "
                        "are read", path, line, len(codes), MAX_CODES_PER_COMMENT)
            codes = codes[:MAX_CODES_PER_COMMENT]
        col = start - (data.rfind(b"\n", 0, start) + 1) + 1
        end_line = line + match.group(0).count(b"\n")
        found.append(Suppression(where, line, end_line, col, codes))
    return found


def scan_files(paths: Iterable[str]) -> list[Suppression]:
    """Find the suppression comments in every readable file of `paths` (others are skipped)."""
    found = []
    for path in dict.fromkeys(paths):
        try:
            with open(path, "rb") as handle:
                data = handle.read()
        except OSError:
            continue
        found.extend(scan_text(data, path))
    return found


def apply_suppressions(diagnostics: Sequence[Diagnostic],
                       suppressions: Sequence[Suppression]) -> SuppressionOutcome:
    """Drop the diagnostics a comment suppresses; record which comment codes were used."""
    kept, suppressed, used = [], [], set()
    for diagnostic in diagnostics:
        hits = [(s, code) for s in suppressions for code in s.codes
                if _names(code, diagnostic) and _covers(s, diagnostic)]
        if hits:
            suppressed.append(diagnostic)
            used.update(hits)
        else:
            kept.append(diagnostic)
    return SuppressionOutcome(tuple(kept), tuple(suppressed), frozenset(used))


def unused_codes(suppressions: Sequence[Suppression],
                 used: frozenset[tuple[Suppression, str]]) -> list[tuple[Suppression, str]]:
    """(suppression, code) pairs that suppressed nothing, in file order."""
    return [(s, code) for s in suppressions for code in s.codes if (s, code) not in used]


def _normalise_code(token: str) -> str:
    return token.upper() if re.fullmatch(r"[A-Za-z]+[0-9]+", token) else token


def _names(code: str, diagnostic: Diagnostic) -> bool:
    return code == diagnostic.code or code == diagnostic.name


def _covers(suppression: Suppression, diagnostic: Diagnostic) -> bool:
    if diagnostic.where is None:
        return False
    spans = (diagnostic.where.span, *diagnostic.where.macro_stack)
    return any(span.line and suppression.covers(normalise_path(span.path), span.line)
               for span in spans)
