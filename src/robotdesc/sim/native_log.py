"""What a native engine prints, caught, counted and attributed to links.

DART writes its warnings (zero-mass frames lumped, the contact budget, mesh problems) with
terminal colours straight to file descriptors 1 and 2, where Python cannot catch them.
`native_output_caught` redirects both descriptors into a temporary file around the native
calls; each line is then logged (debug) and counted in a `NativeMessages`: the message with
link and joint names replaced by `<link>` and numbers by `#`, how often, and on which links
(a joint's name counts for its child link).
"""

from __future__ import annotations

import contextlib
import ctypes
import logging
import os
import re
import sys
import tempfile
from collections import Counter
from collections.abc import Iterator, Mapping
from dataclasses import dataclass

_ANSI = re.compile(r"\x1b\[[0-9;]*m")
_TOKEN = re.compile(r"[A-Za-z_][A-Za-z0-9_\-./]*")
_NUMBER = re.compile(r"(?<![A-Za-z_])[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")


@dataclass(frozen=True)
class NativeMessage:
    """One kind of native message.

    Attributes:
        text: the message, link names as `<link>`, numbers as `#`.
        count: how often it was printed.
        links: (link, count) of the links it named, most often first.
    """

    text: str
    count: int
    links: tuple[tuple[str, int], ...] = ()


class NativeMessages:
    """Native output lines of one scene, counted per kind and link (not thread-safe)."""

    def __init__(self, links: Mapping[str, str] | None = None) -> None:
        """`links`: name -> link for every name that means a link (links and joints)."""
        self._names = dict(links or {})
        self._counts: Counter[str] = Counter()
        self._links: dict[str, Counter[str]] = {}

    def add(self, line: str) -> None:
        """Count one line (colour codes and blanks ignored)."""
        text = _ANSI.sub("", line).strip()
        if not text:
            return
        named = [self._names[t] for t in _TOKEN.findall(text) if t in self._names]
        for token in sorted({t for t in _TOKEN.findall(text) if t in self._names},
                            key=len, reverse=True):
            text = re.sub(rf"(?<![\w\-./]){re.escape(token)}(?![\w\-./])", "<link>", text)
        text = _NUMBER.sub("#", text)
        self._counts[text] += 1
        per_link = self._links.setdefault(text, Counter())
        for link in set(named):
            per_link[link] += 1

    @property
    def total(self) -> int:
        """Lines counted."""
        return sum(self._counts.values())

    def messages(self) -> tuple[NativeMessage, ...]:
        """Each kind, most frequent first."""
        return tuple(NativeMessage(text, count, tuple(self._links[text].most_common()))
                     for text, count in self._counts.most_common())


@contextlib.contextmanager
def native_output_caught(logger: logging.Logger,
                         messages: NativeMessages | None = None) -> Iterator[None]:
    """Redirect file descriptors 1 and 2 meanwhile; log each line (debug) and count it."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    with tempfile.TemporaryFile() as sink:
        os.dup2(sink.fileno(), 1)
        os.dup2(sink.fileno(), 2)
        try:
            yield
        finally:
            _flush_native()
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            for fd in saved:
                os.close(fd)
            sink.seek(0)
            for line in sink.read().decode("utf-8", "replace").splitlines():
                if line.strip():
                    logger.debug("dart: %s", _ANSI.sub("", line).strip())
                    if messages is not None:
                        messages.add(line)


def _flush_native() -> None:
    """Flush C stdio buffers (C++ streams synchronised with stdio write through them)."""
    try:
        ctypes.CDLL(None).fflush(None)
    except (OSError, AttributeError):
        pass
