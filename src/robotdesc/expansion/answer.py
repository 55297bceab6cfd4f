"""The worker's answer is untrusted data: parse it strictly, and justify every path in it.

The worker ran code from the description (a xacro file can write its own answer to the
answer pipe and exit), so nothing in the answer is believed: its shape is checked against a
strict schema (types, sizes, counts) and every path it names (spans, call stacks, macro
sites, argument declarations, included and read files) must be one the parent can justify
itself: absolute, inside the data roots it granted (by real path, so no symlink leads out
of them), and a regular file. Anything else is "the xacro worker sent an invalid answer"
(exit 2), never shown. A failure the worker reports is the input's failure (exit 2),
whatever kind it names: the worker cannot speak for robotdesc's own bugs.

The same check runs on an expansion read back from the cache (`check_expanded`): a cache
folder can be shared, and an entry planted.
"""

from __future__ import annotations

import os
import re
import stat
from collections.abc import Callable, Iterable
from pathlib import Path

from robotdesc import errors
from robotdesc.expansion.result import EnvDefault, Expanded, MacroRecursion, ResolvedPackage
from robotdesc.expansion.roots import Roots
from robotdesc.printable import printable
from robotdesc.source import PASSED_SEPARATOR, PROVENANCE_ATTR, Span
from robotdesc.trust import RealPaths, real_within

#: Longest message, name or path taken from an answer (characters).
MAX_TEXT = 8192
#: Most entries of any list in an answer (files, spans, packages, arguments).
MAX_ITEMS = 200_000
#: Largest line or column number in a span.
MAX_LINE = 1 << 31
#: The failure kinds a worker reports, and the input error each becomes.
FAILURE_KINDS: dict[str, type[errors.InputError]] = {
    "XmlSyntaxError": errors.XmlSyntaxError,
    "ExpansionError": errors.ExpansionError,
    "SandboxViolation": errors.SandboxViolation,
    "LimitExceeded": errors.LimitExceeded,
    "PackageNotFoundError": errors.ExpansionError,
    "SandboxUnavailable": errors.SandboxUnavailable,
    # the worker's own catch-all: still the input's failure, the expansion of this file
    # could not finish (robotdesc cannot tell its bug from a hostile answer here)
    "InternalError": errors.ExpansionError,
}
#: A path in an answer that is no file: xacro's name for text given inline.
_INLINE = "<string>"


def invalid(path: Path, why: str) -> errors.InvalidAnswer:
    """The error for an answer refused because of `why` (no value from the answer in it)."""
    return errors.InvalidAnswer(f"the xacro worker sent an invalid answer ({why}); the sandbox "
                         "refused the result", Span(str(path)))


def _text(value: object, what: str, path: Path, limit: int = MAX_TEXT) -> str:
    if not isinstance(value, str) or len(value) > limit:
        raise invalid(path, f"{what} is not text of at most {limit} characters")
    return value


def _count(value: object, what: str, path: Path) -> int:
    if not isinstance(value, int) or isinstance(value, bool) or not 0 <= value < MAX_LINE:
        raise invalid(path, f"{what} is not a line, column or depth")
    return value


def _list(value: object, what: str, path: Path, size: int | None = None) -> list[object]:
    if not isinstance(value, list) or len(value) > MAX_ITEMS \
            or (size is not None and len(value) != size):
        raise invalid(path, f"{what} is not a list of the expected size")
    return value


class _Reader:
    """Turns the parts of one answer into values, collecting every path it names."""

    def __init__(self, top: Path) -> None:
        self.top = top
        self.paths: list[str] = []

    def path(self, value: object, what: str) -> str:
        name = _text(value, what, self.top, 4096)
        self.paths.append(name)
        return name

    def span(self, value: object, what: str) -> Span | None:
        if value is None:
            return None
        items = _list(value, what, self.top)
        if len(items) not in (2, 3):
            raise invalid(self.top, f"{what} is not [file, line, column]")
        column = _count(items[2], what, self.top) if len(items) == 3 else 0
        return Span(self.path(items[0], what), _count(items[1], what, self.top), column)

    def spans(self, value: object, what: str) -> tuple[Span, ...]:
        return tuple(s for s in (self.span(v, what) for v in _list(value, what, self.top)) if s)

    def texts(self, value: object, what: str) -> tuple[str, ...]:
        return tuple(_text(v, what, self.top) for v in _list(value, what, self.top))

    def rows(self, value: object, what: str, size: int) -> list[list[object]]:
        return [_list(row, what, self.top, size) for row in _list(value, what, self.top)]


def parse_failure(answer: dict[str, object], top: Path) -> tuple[errors.InputError, list[str]]:
    """The input error a failure answer reports, and the paths it names (to be justified)."""
    reader = _Reader(top)
    kind = _text(answer.get("kind"), "kind", top, 64)
    if kind not in FAILURE_KINDS:
        raise invalid(top, "an unknown failure kind")
    message = printable(_text(answer.get("message"), "message", top))
    span = reader.span(answer.get("span"), "span") or Span(str(top))
    chain = reader.spans(answer.get("call_stack", []), "call_stack")
    if kind == "InternalError":
        message = f"the expansion failed inside the xacro worker: {message}"
    return FAILURE_KINDS[kind](message, span, chain), reader.paths


def parse_expanded(answer: dict[str, object], top: Path, args: dict[str, str],
                   max_output_bytes: int) -> Expanded:
    """The expansion a success answer carries (its paths: `expanded_paths`)."""
    reader = _Reader(top)
    xml = _text(answer.get("xml"), "xml", top, max_output_bytes)
    files = tuple(reader.path(v, "files") for v in _list(answer.get("files"), "files", top))
    files_read = tuple(reader.path(v, "files_read")
                       for v in _list(answer.get("files_read"), "files_read", top))
    packages = tuple(ResolvedPackage(*(_text(v, "packages", top) for v in row))
                     for row in reader.rows(answer.get("packages"), "packages", 3))
    recursion = tuple(
        MacroRecursion(_text(name, "macro_recursion", top), _count(depth, "depth", top),
                       reader.span(defined, "macro_recursion") or Span(str(top)),
                       reader.span(called, "macro_recursion"))
        for name, depth, defined, called in reader.rows(answer.get("macro_recursion"),
                                                        "macro_recursion", 4))
    declared = tuple((_text(name, "declared_args", top),
                      reader.span(span, "declared_args") or Span(str(top)))
                     for name, span in reader.rows(answer.get("declared_args", []),
                                                   "declared_args", 2))
    env_defaults = tuple(
        EnvDefault(_text(name, "env_defaults", top), _text(default, "env_defaults", top),
                   reader.span(span, "env_defaults") or Span(str(top)))
        for name, default, span in reader.rows(answer.get("env_defaults", []),
                                               "env_defaults", 3))
    return Expanded(
        source=str(top), xml=xml.encode("utf-8"), files=files, files_read=files_read,
        packages=packages, macro_recursion=recursion, from_xacro=True,
        args=tuple(sorted(args.items())), declared_args=declared,
        read_args=reader.texts(answer.get("read_args", []), "read_args"),
        env_defaults=env_defaults)


def justified(name: str, roots: tuple[str, ...],
              real_path: Callable[[str], str] = os.path.realpath) -> bool:
    """True when the parent itself can vouch for `name` as part of the description: an
    absolute path whose real path lies inside `roots` and is a regular file (or xacro's
    `<string>`). `real_path`: as `robotdesc.trust.real_within` takes it."""
    if name == _INLINE:
        return True
    if not os.path.isabs(name) or "\x00" in name:
        return False
    if not real_within(name, roots, real_path):
        return False
    try:
        return stat.S_ISREG(os.stat(name).st_mode)
    except (OSError, ValueError):
        return False


def check_paths(paths: Iterable[str], roots: Roots, top: Path) -> None:
    """Refuse (exit 2) an answer naming a path the parent cannot justify.

    Raises:
        InvalidAnswer: a path outside the data roots, not a regular file, or not absolute.
    """
    real_path = RealPaths()  # the answer's files share a few folders: each resolved once
    for name in dict.fromkeys(paths):
        if not justified(name, roots.data, real_path):
            raise invalid(top, "it names a file outside the packages in use")


def check_packages(expanded: Expanded, roots: Roots, top: Path) -> None:
    """Refuse an answer naming a package the parent's resolver does not know."""
    known = set(roots.known)
    if any(package not in known for package in expanded.packages):
        raise invalid(top, "it names a package the resolver does not know")


def expanded_paths(expanded: Expanded) -> list[str]:
    """Every path an `Expanded` names (files, spans), for `check_paths`."""
    spans: list[Span | None] = [*(s for _, s in expanded.declared_args),
                                *(d.span for d in expanded.env_defaults)]
    for recursion in expanded.macro_recursion:
        spans.extend((recursion.defined_at, recursion.called_at))
    return [*expanded.files, *expanded.files_read, *(s.path for s in spans if s is not None)]


def check_expanded(expanded: Expanded, roots: Roots, top: Path, max_chain: int) -> None:
    """Every check on a whole expansion: a worker's answer, or one read back from the cache.

    Raises:
        InvalidAnswer: a path or package the parent cannot justify, malformed provenance.
    """
    check_paths(expanded_paths(expanded), roots, top)
    check_packages(expanded, roots, top)
    check_provenance(expanded, top, max_chain)


_PROVENANCE = re.compile(rb"\s" + PROVENANCE_ATTR.encode() + rb"""=(?:"([^"]*)"|'([^']*)')""")
_SITE = re.compile(r"([0-9]{1,9}):([0-9]{1,10})(?:\*([0-9]{1,9}))?")


def _chain_total(chain: str, files: int) -> int | None:
    """How many call sites a chain ("SITE;SITE*N;...") stands for; None when a site is
    malformed or indexes past the file table."""
    total = 0
    for part in chain.split(";"):
        site = _SITE.fullmatch(part)
        if site is None or int(site.group(1)) >= files:
            return None
        total += int(site.group(3) or 1)
    return total


def _valid_provenance(value: str, files: int, max_chain: int,
                      chains: dict[str, int | None]) -> bool:
    """Whether one provenance value decodes within the file table and the chain bound.

    Args:
        chains: `_chain_total` of the call chains seen so far (after an element's own site):
            the elements of one macro call share theirs.
    """
    chain, _, passed = value.partition(PASSED_SEPARATOR)
    own, calls, rest = chain.partition(";")
    total = _chain_total(own, files)
    if calls and total is not None:
        if rest not in chains:
            chains[rest] = _chain_total(rest, files)
        more = chains[rest]
        total = None if more is None else total + more
    if total is None or total > max_chain:
        return False
    for item in passed.split(",") if passed else ():
        name, _, where = item.rpartition("@")
        site = _SITE.fullmatch(where)
        if not name or site is None or site.group(3) or int(site.group(1)) >= files:
            return False
    return True


def max_chain(max_macro_depth: int) -> int:
    """The longest macro chain an element may claim: one site per nesting level, and the
    include and call sites around them."""
    return 2 * max_macro_depth + 64


def check_provenance(expanded: Expanded, top: Path, max_chain: int) -> None:
    """Refuse provenance attributes that index past the file table, are malformed, or
    claim a macro chain longer than `max_chain` (a forged `*999999999` would make the
    parent build a billion spans).

    Raises:
        InvalidAnswer: such an attribute.
    """
    chains: dict[str, int | None] = {}
    for match in _PROVENANCE.finditer(expanded.xml):
        raw = match.group(1) if match.group(1) is not None else match.group(2)
        if not _valid_provenance(raw.decode("ascii", "replace"), len(expanded.files),
                                 max_chain, chains):
            raise invalid(top, "malformed provenance in the document")
