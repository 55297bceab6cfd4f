"""The replay of an unchanged lint: `robotdesc lint FILE...` run again with the same command
line, environment and terminal, on files that did not change since, prints what the last such
run printed, before the argument parser or any of the lint machinery is imported (issue 31: a
warm run is a cache read).

A run that the whole-result cache answered entirely (`commands/lint.py`) is recorded in a
sealed entry (`cache_dir.write_entry`: the cache key of this user or of `ROBOTDESC_CACHE_KEY`)
under a key made of robotdesc's code, the backends that change findings, the interpreter, the
command line, the working folder, the whole environment and whether stdout and stderr are
terminals (and how wide): its exit code, what it wrote on stdout and stderr, the identity and
digest of every file its answer depended on, and for each file argument its real path and the
config file that applies to it. A later run with the same key replays it when
- every recorded file still has its identity (`digest.file_stamp`), or else its digest, and
  its folder is its own real path (no symlink put on the way);
- each argument is the same regular file and finds the same config (`config.files`: a config
  put above it since is noticed).
Otherwise (or when the entry is missing, malformed or not sealed with the key) the lint runs
as usual, and the whole-result cache answers what it can.

Recorded are only runs that write no file (no --output-file, --fix, --diff or baseline), whose
arguments are files (a folder's search depends on its listing), that exit 0 or 1, and none
whose inputs changed within `SETTLE_NS` of the run (a file system's timestamp granularity).
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
import time
from collections.abc import Sequence
from types import TracebackType
from typing import NamedTuple, TextIO

from robotdesc.code_stamp import FINDING_BACKENDS, code_id, module_stamp
from robotdesc.cache_dir import cache_root, entry_file, read_entry, write_entry
from robotdesc.config.files import find_config_file
from robotdesc.digest import FileStamp, file_digest, file_stamp
from robotdesc.errors import InputError

_FORMAT = 1
#: The largest entry read or written (a report of many findings is a few hundred kB).
MAX_ENTRY_BYTES = 16 << 20
#: Inputs changed within this much of the run are not trusted by their identity (ns).
SETTLE_NS = 2_000_000_000
_EXIT_CODES = (0, 1)


class CheckedFile(NamedTuple):
    """A file the answer depended on, as the run verified it.

    Attributes:
        path: its real path.
        stamp: its identity (`digest.file_stamp`).
        digest: the SHA-256 of its bytes, hex.
    """

    path: str
    stamp: FileStamp
    digest: str


class Argument(NamedTuple):
    """A file named on the command line.

    Attributes:
        word: as written.
        real: its real path.
        config: the config file that applies to it (`find_config_file`), or None.
    """

    word: str
    real: str
    config: str | None


class _Entry(NamedTuple):
    """A recorded run, as read back: its exit code, output and what it depended on."""

    code: int
    out: str
    err: str
    files: list[CheckedFile]
    arguments: list[Argument]


class ReplayRecord(NamedTuple):
    """What makes a run replayable: the files its answer depended on and its arguments."""

    files: tuple[CheckedFile, ...]
    arguments: tuple[Argument, ...]


def argument(word: str) -> Argument:
    """The record of one file argument, as the replay will check it."""
    return Argument(word, os.path.realpath(word), find_config_file(os.path.abspath(word)))


def replay(words: Sequence[str]) -> int | None:
    """Print what the recorded run of `words` (a `robotdesc lint` command line) printed and
    return its exit code, when it is recorded and nothing it depended on changed; else None
    (the caller lints)."""
    root = cache_root()
    if root is None:
        return None
    key = replay_key(words)
    raw = read_entry(entry_file(root / "replay", key), MAX_ENTRY_BYTES)
    if raw is None:
        return None
    try:
        entry = _parsed(json.loads(raw), key)
        if entry is None or not _unchanged(entry.files, entry.arguments):
            return None
    except (ValueError, TypeError, KeyError, IndexError, AttributeError, OSError,
            RecursionError, InputError):  # a malformed entry, a file gone: a miss
        return None
    sys.stderr.write(entry.err)
    sys.stdout.write(entry.out)
    sys.stdout.flush()
    return entry.code


def replay_key(words: Sequence[str]) -> str:
    """The key of a run: everything besides file contents that can change what it prints."""
    material = [
        _FORMAT, code_id(), [module_stamp(name) for name in FINDING_BACKENDS],
        sys.version, sys.executable, list(words), os.getcwd(), sorted(os.environ.items()),
        _terminal(sys.stdout), _terminal(sys.stderr),
    ]
    return hashlib.sha256(json.dumps(material).encode()).hexdigest()


def _terminal(stream: TextIO) -> list[int] | None:
    """Whether `stream` is a terminal, and its size (text reports are coloured there)."""
    try:
        if not stream.isatty():
            return None
        size = os.get_terminal_size(stream.fileno())
        return [size.columns, size.lines]
    except (AttributeError, ValueError, OSError):
        return None


def _parsed(record: object, key: str) -> _Entry | None:
    """The entry's fields when it has the expected shape and key; None otherwise."""
    if not isinstance(record, dict) or record.get("format") != _FORMAT \
            or record.get("key") != key:
        return None
    code, out, err = record["code"], record["out"], record["err"]
    if code not in _EXIT_CODES or not isinstance(out, str) or not isinstance(err, str):
        return None
    files = []
    for item in record["files"]:
        path, stamp, digest = item
        if not (isinstance(path, str) and os.path.isabs(path) and isinstance(digest, str)
                and len(digest) == 64 and isinstance(stamp, list) and len(stamp) == 5
                and all(type(part) is int for part in stamp)):
            return None
        files.append(CheckedFile(path, (stamp[0], stamp[1], stamp[2], stamp[3], stamp[4]),
                                 digest))
    arguments = []
    for item in record["arguments"]:
        word, real, config = item
        if not (isinstance(word, str) and isinstance(real, str)
                and (config is None or isinstance(config, str))):
            return None
        arguments.append(Argument(word, real, config))
    if not files or not arguments:
        return None
    return _Entry(code, out, err, files, arguments)


def _unchanged(files: list[CheckedFile], arguments: list[Argument]) -> bool:
    """Whether every recorded file and argument is as the recorded run found it."""
    real_folders: dict[str, bool] = {}
    for item in files:
        folder = os.path.dirname(item.path)
        if folder not in real_folders:
            real_folders[folder] = os.path.realpath(folder) == folder
        if not real_folders[folder]:
            return False
        stamp = file_stamp(item.path)
        if stamp is None:
            return False
        if stamp != item.stamp and file_digest(item.path, follow_symlinks=False) != item.digest:
            return False
    return all(os.path.isfile(arg.word) and argument(arg.word) == arg for arg in arguments)


class _Tee:
    """A text stream that keeps a copy of what is written through it, up to
    `MAX_ENTRY_BYTES` characters (a long lint's progress on a terminal is not kept)."""

    def __init__(self, stream: TextIO) -> None:
        self.stream = stream
        self.parts: list[str] = []
        self.kept = 0
        self.overflow = False

    def write(self, text: str) -> int:
        if not self.overflow:
            self.kept += len(text)
            self.overflow = self.kept > MAX_ENTRY_BYTES
            self.parts.append(text)
            if self.overflow:
                self.parts.clear()
        return self.stream.write(text)

    def __getattr__(self, name: str) -> object:  # isatty, flush, fileno, encoding, ...
        return getattr(self.stream, name)


class Recording:
    """While active (a `with` block around a lint), keeps a copy of what the run writes on
    stdout and stderr, for `store`; a pass-through when the caches are off."""

    def __init__(self) -> None:
        self.active = cache_root() is not None
        self.started_ns = time.time_ns()
        self._tees: tuple[_Tee, _Tee] | None = None

    def __enter__(self) -> None:
        if self.active:
            self._tees = (_Tee(sys.stdout), _Tee(sys.stderr))
            sys.stdout, sys.stderr = self._tees

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        if self._tees is not None:
            sys.stdout, sys.stderr = self._tees[0].stream, self._tees[1].stream

    def out(self) -> str:
        """What was written on stdout."""
        return "".join(self._tees[0].parts) if self._tees else ""

    def err(self) -> str:
        """What was written on stderr."""
        return "".join(self._tees[1].parts) if self._tees else ""

    def store(self, words: Sequence[str], record: ReplayRecord, code: int) -> None:
        """Record a run whose answer came whole from the cache, for `replay`; nothing when one of
        its inputs changed during or shortly before it, or its output is too large."""
        root = cache_root()
        if root is None or not self.active or code not in _EXIT_CODES or not record.files \
                or not record.arguments or any(tee.overflow for tee in self._tees or ()):
            return
        settled = self.started_ns - SETTLE_NS
        for item in record.files:
            if file_stamp(item.path) != item.stamp or max(item.stamp[3], item.stamp[4]) >= settled:
                return
        key = replay_key(words)
        entry = {"format": _FORMAT, "key": key, "code": code,
                 "out": self.out(), "err": self.err(),
                 "files": [[f.path, list(f.stamp), f.digest] for f in record.files],
                 "arguments": [list(a) for a in record.arguments]}
        data = json.dumps(entry).encode()
        if len(data) <= MAX_ENTRY_BYTES:
            write_entry(entry_file(root / "replay", key), data)
