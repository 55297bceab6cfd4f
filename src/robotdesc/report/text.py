"""Human-readable report, in the manner of ruff and rustc.

    urdf/arm.urdf.xacro:12:5: J102 [error] revolute joint 'elbow' has no <limit>
       |
    12 |     <joint name="${prefix}elbow" type="revolute">
       |     ^^^^^^
       = in macro called from urdf/robot.urdf.xacro:40
       = fix: <limit lower="-1.57" upper="1.57" effort="10" velocity="1"/>

    Found 1 error in 1 file.

Colour (via rich, imported only when used) is for terminals only.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING, TextIO

from robotdesc.cache_dir import read_regular_file
from robotdesc.diagnostics import Diagnostic, Severity
from robotdesc.errors import InputError
from robotdesc.linting.merge import LISTED_ELEMENTS, MergedFinding, merge_findings
from robotdesc.printable import printable
from robotdesc.source import Span, passed_sites

if TYPE_CHECKING:
    from robotdesc.linting.result import LintFailure, LintResult

Segment = tuple[str, str]  # (text, rich style; "" for none)
Line = list[Segment]

_SEVERITY_STYLE = {Severity.ERROR: "bold red", Severity.WARNING: "bold yellow",
                   Severity.INFO: "bold blue"}
_TAG_START = re.compile(r"</?[A-Za-z_][\w:.-]*")
#: Characters of a source line shown under a finding.
_SOURCE_WINDOW = 200


#: The largest source file whose lines are shown (bytes).
_MAX_SOURCE_BYTES = 64 << 20


class SourceCache:
    """Reads source lines once per file; a file that cannot be read has no lines.

    Only regular files are read (never a symlink, FIFO or device a span might name),
    without blocking and up to `_MAX_SOURCE_BYTES`. Which files a span may name at all is decided
    where spans enter robotdesc (the worker's answer, the caches): see docs/security.md.
    """

    def __init__(self) -> None:
        self._lines: dict[str, list[str]] = {}

    def line(self, path: str, number: int) -> str | None:
        if path not in self._lines:
            data = read_regular_file(path, _MAX_SOURCE_BYTES)
            self._lines[path] = [] if data is None else \
                data.decode("utf-8", "replace").splitlines()
        lines = self._lines[path]
        return lines[number - 1] if 0 < number <= len(lines) else None


def display_path(path: str, cwd: str | None = None) -> str:
    """`path` relative to the working directory when it lies under it, else as is."""
    base = cwd or os.getcwd()
    absolute = os.path.abspath(path)
    try:
        relative = os.path.relpath(absolute, base)
    except ValueError:  # another drive (Windows)
        return absolute
    return absolute if relative.startswith("..") else relative


def render_lines(results: Sequence[LintResult], failures: Sequence[LintFailure] = (), *,
                 cwd: str | None = None, show_source: bool = True) -> list[Line]:
    """The report as styled lines.

    Args:
        results: `LintResult`s (each with `diagnostics`).
        failures: `LintFailure`s (files that could not be checked); counted in the summary
            only, see `render_failure` for their text.
        cwd: the directory paths are shown relative to (default: the working directory).
        show_source: include the source line and caret under each diagnostic.
    """
    cache = SourceCache()
    shown: dict[str, str] = {}

    def show(path: str) -> str:
        if path not in shown:
            shown[path] = display_path(path, cwd)
        return shown[path]

    lines: list[Line] = []
    for finding in merge_findings(results):
        found = _diagnostic_lines(finding.diagnostic, show, cache, show_source)
        note = finding.variant_note()
        if note:  # only some variants of its target: say which
            found[0] = [*found[0], (note, "")]
        lines.extend(found)
        lines.extend(merged_lines(finding, show))
        lines.append([])
    lines.append(summary_line(results, failures))
    lines.extend(checked_lines(results, show))
    return lines


#: Variants listed by name under the summary; more are counted.
_LISTED_VARIANTS = 10


def variant_text(result: LintResult, show: Callable[[str], str] = display_path) -> str:
    """A linted variant by name and arguments: `urdf/a.urdf.xacro hand:=false` (or
    `(default arguments)`)."""
    args = getattr(result, "args", ()) or getattr(result, "variant", ())
    shown = " ".join(f"{name}:={value}" for name, value in args)
    return f"{show(result.target)} {shown or '(default arguments)'}"


def suppressed_counts(results: Sequence[LintResult]) -> dict[str, int]:
    """Findings hidden, by mechanism: inline comments, config ignores, baseline."""
    return {"inline": sum(getattr(r, "suppressed", 0) for r in results),
            "config": sum(getattr(r, "suppressed_by_config", 0) for r in results),
            "baseline": sum(getattr(r, "suppressed_by_baseline", 0) for r in results)}


def files_read(results: Sequence[LintResult]) -> int:
    """The number of distinct files the lints read (descriptions, includes, configs,
    package.xml, meshes)."""
    return len(set().union(*(getattr(r, "files_read", frozenset()) for r in results)))


def checked_lines(results: Sequence[LintResult],
                  show: Callable[[str], str] = display_path) -> list[Line]:
    """What was checked, under the summary: the variants linted (when a file was linted
    with arguments or more than once), the findings suppressed and the files read."""
    if not results:
        return []
    lines: list[Line] = []
    several = len({r.target for r in results}) < len(results)
    if several or any(getattr(r, "args", ()) or getattr(r, "variant", ()) for r in results):
        lines.append([(f"Linted {_plural(len(results), 'variant')}:", "")])
        lines.extend([(f"  {variant_text(r, show)}", "")] for r in results[:_LISTED_VARIANTS])
        if len(results) > _LISTED_VARIANTS:
            lines.append([(f"  ... {len(results) - _LISTED_VARIANTS} more", "")])
    counts = suppressed_counts(results)
    words = {"inline": "inline comments", "config": "config ignores", "baseline": "baseline"}
    text = f"Read {_plural(files_read(results), 'file')}"
    if sum(counts.values()):
        text += (f"; {_plural(sum(counts.values()), 'finding')} suppressed ("
                 + ", ".join(f"{n} by {words[k]}" for k, n in counts.items() if n) + ")")
    lines.append([(text + ".", "dim")])
    return lines


def render_text(results: Sequence[LintResult], failures: Sequence[LintFailure] = (), *,
                cwd: str | None = None, show_source: bool = True) -> str:
    """The report as plain text (no colour), ending with a newline."""
    return _joined(render_lines(results, failures, cwd=cwd, show_source=show_source))


def _joined(lines: Iterable[Line]) -> str:
    """Lines as text, each segment `printable`: a name or message holding a newline or an
    escape (a link named `a&#10;::error ...`) stays on its line (see robotdesc.printable)."""
    return "".join("".join(printable(text) for text, _ in line) + "\n" for line in lines)


def write_text(stream: TextIO, results: Sequence[LintResult],
               failures: Sequence[LintFailure] = (), *,
               colour: bool = False, cwd: str | None = None) -> None:
    """Write the report to `stream`, coloured with rich when `colour` is set."""
    lines = render_lines(results, failures, cwd=cwd)
    if not colour:
        stream.write(_joined(lines))
        return
    from rich.console import Console
    from rich.text import Text

    console = Console(file=stream, force_terminal=True, highlight=False, soft_wrap=True,
                      emoji=False, markup=False)
    for line in lines:
        rendered = Text()
        for text, style in line:
            rendered.append(printable(text), style or None)
        console.print(rendered)


def render_failure(failure: LintFailure, *, cwd: str | None = None, show_source: bool = True) -> str:
    """A file that could not be checked: `path:line:col: error: message`, the source line
    and the macro call chain (plain text, ending with a newline)."""
    show = lambda path: display_path(path, cwd)
    return _joined(_failure_lines(failure.error, failure.target, show, SourceCache(),
                                  show_source))


def merged_lines(finding: MergedFinding, show: Callable[[str], str]) -> list[Line]:
    """Under a merged finding: its elements (when a macro line made several, each with the
    call site that made it) and, when its target was linted in several variants and it
    occurs in all, the variants (the head line names the variants of one found in some)."""
    diagnostic = finding.diagnostic
    span = diagnostic.where.span if diagnostic.where else None
    gutter = " " * (len(str(span.line)) if span and span.line else 1)
    lines: list[Line] = []
    if len(finding.elements) > 1:
        sites: dict[str, str] = {}
        for occurrence in finding.occurrences:
            stack = occurrence.where.macro_stack if occurrence.where else ()
            if occurrence.element not in sites:
                sites[occurrence.element] = (f" (from {_location(stack[0], show, '')})"
                                             if stack else "")
        listed = ", ".join(f"{element}{sites.get(element, '')}"
                           for element in finding.elements[:LISTED_ELEMENTS])
        more = len(finding.elements) - LISTED_ELEMENTS
        listed += f", ... {more} more" if more > 0 else ""
        lines.append([(f"{gutter} = ", "blue"),
                      (f"{len(finding.elements)} elements: {listed}", "")])
    variants = finding.variants_text() if finding.in_all_variants else ""  # else: head line
    if variants:
        lines.append([(f"{gutter} = ", "blue"), (variants, "")])
    return lines


def summary_line(results: Sequence[LintResult], failures: Sequence[LintFailure] = ()) -> Line:
    """"Found 3 errors, 1 warning in 2 files." / "All checks passed (2 files)." (a finding
    repeated over variants and elements counts once)."""
    totals = {level: 0 for level in sorted(Severity, reverse=True)}
    files = set()
    for finding in merge_findings(results):
        diagnostic = finding.diagnostic
        totals[diagnostic.severity] += 1
        files.add(diagnostic.where.span.path if diagnostic.where else diagnostic.target)
    parts = [_plural(n, str(level)) for level, n in totals.items() if n]
    line: Line
    if parts:
        line = [(f"Found {', '.join(parts)} in {_plural(len(files), 'file')}.", "bold")]
    elif results:
        targets = len({r.target for r in results})
        checked = _plural(targets, 'file') if targets == len(results) else \
            f"{_plural(len(results), 'variant')} of {_plural(targets, 'file')}"
        line = [(f"All checks passed ({checked} checked).", "bold green")]
    else:
        line = []
    if failures:
        text = f"{_plural(len(failures), 'file')} could not be checked."
        line = line + [(" " if line else "", ""), (text, "bold red")]
    return line


def _plural(count: int, noun: str) -> str:
    return f"{count} {noun}" if count == 1 else f"{count} {noun}s"


def _location(span: Span | None, show: Callable[[str], str], fallback: str) -> str:
    if span is None:
        return show(fallback)
    return str(Span(show(span.path), span.line, span.col))


def _diagnostic_lines(diagnostic: Diagnostic, show: Callable[[str], str], cache: SourceCache,
                      show_source: bool) -> list[Line]:
    span = diagnostic.where.span if diagnostic.where else None
    head: Line = [(_location(span, show, diagnostic.target), "bold"), (": ", ""),
                  (diagnostic.code, "bold magenta"), (" ", ""),
                  (f"[{diagnostic.severity}]", _SEVERITY_STYLE[diagnostic.severity]),
                  (f" {diagnostic.message}", "")]
    lines = [head]
    stack = diagnostic.where.macro_stack if diagnostic.where else ()
    lines.extend(_context_lines(span, stack, show, cache, show_source))
    gutter = " " * (len(str(span.line)) if span and span.line else 1)
    for site, names in passed_sites(diagnostic.where.passed if diagnostic.where else ()):
        passed = f"value passed at {_location(site, show, site.path)} ({', '.join(names)})"
        lines.append([(f"{gutter} = ", "blue"), (passed, "")])
    if diagnostic.fix:
        gutter = " " * (len(str(span.line)) if span and span.line else 1)
        fix_lines = diagnostic.fix.strip("\n").splitlines()
        lines.append([(f"{gutter} = ", "blue"), ("fix:", "bold green")])
        lines.extend([(f"{gutter}   ", "blue"), (text, "green")] for text in fix_lines)
    return lines


def _failure_lines(error: InputError, target: str, show: Callable[[str], str],
                   cache: SourceCache, show_source: bool) -> list[Line]:
    span = getattr(error, "span", None)
    message = getattr(error, "message", str(error))
    head: Line = [(_location(span, show, target), "bold"), (": ", ""), ("error", "bold red"),
                  (f": {message}", "")]
    stack = getattr(error, "call_stack", ())
    return [head, *_context_lines(span, stack, show, cache, show_source)]


def _context_lines(span: Span | None, stack: Iterable[Span], show: Callable[[str], str],
                   cache: SourceCache, show_source: bool) -> list[Line]:
    """The source line with a caret under the element, then the macro call chain."""
    lines: list[Line] = []
    source = cache.line(span.path, span.line) if (span and span.line and show_source) else None
    width = len(str(span.line)) if span and span.line else 1
    gutter = " " * width
    if source is not None and span is not None:
        source, col = _clip_source(source.rstrip(), span.col)
        start, length = _underline(source, col)
        lines.append([(f"{gutter} |", "blue")])
        lines.append([(f"{span.line} | ", "blue"), (source.expandtabs(4), "")])
        lines.append([(f"{gutter} | ", "blue"), (" " * start, ""), ("^" * length, "bold red")])
    for site, repeats in _runs(stack):
        again = f" ({repeats} nested calls from this line)" if repeats > 1 else ""
        lines.append([(f"{gutter} = ", "blue"),
                      (f"in macro called from {_location(site, show, site.path)}{again}", "")])
    return lines


def _clip_source(source: str, col: int) -> tuple[str, int]:
    """A long source line cut to a window around `col` (1-based), and the column within it,
    so that a report grows with the number of findings, not with the length of their lines."""
    if len(source) <= _SOURCE_WINDOW:
        return source, col
    start = max(0, col - 1 - _SOURCE_WINDOW // 2)
    window = source[start:start + _SOURCE_WINDOW]
    if start:
        window = "..." + window
    if start + _SOURCE_WINDOW < len(source):
        window += "..."
    return window, (col - start + (3 if start else 0)) if col else 0


def _runs(stack: Iterable[Span]) -> list[tuple[Span, int]]:
    """Consecutive identical call sites (a recursive macro) as (site, count)."""
    runs: list[tuple[Span, int]] = []
    for site in stack:
        if runs and runs[-1][0] == site:
            runs[-1] = (site, runs[-1][1] + 1)
        else:
            runs.append((site, 1))
    return runs


def _underline(source: str, col: int) -> tuple[int, int]:
    """Caret position (0-based display column, length) under the tag at `col` (1-based).

    Without a column, the first non-blank character. Tabs count as 4 display columns.
    """
    start = col - 1 if 0 < col <= len(source) else len(source) - len(source.lstrip())
    tag = _TAG_START.match(source, start)
    length = (tag.end() - start) if tag else 1
    return len(source[:start].expandtabs(4)), length
