"""Mesh summaries computed by two processes at once: this one and a forked child (a cold
lint: the meshes of a description are summarized on both cores, the one the xacro worker
has just left and this one).

The jobs are shared through a page both processes see (`mmap`, one byte per job: whose it
is). The child takes the COLLADA files first when pycollada is not imported here (they are
its alone: the import is made once, there), then the unclaimed jobs from the largest file
down; this process, asked for
a job (`take`), summarizes it itself when nobody claimed it, and while the child works on it,
takes the smallest unclaimed jobs meanwhile. Two claims at the same moment only mean a file
summarized twice. The child is a fork of this process (numpy and the mesh readers are
imported already); it writes one JSON line per summary on a pipe, as the mesh cache stores
them (`summary_to_json`); this process reads them as it reads a cache entry
(`summary_from_json`: shapes checked). A job the child failed on, or left when it ended, is
summarized here. The fork, and when one is allowed (`can_fork`), are `robotdesc.forked`'s.
"""

from __future__ import annotations

import json
import logging
import mmap
import os
import sys
from collections.abc import Callable, Sequence

from robotdesc.forked import Forked, write_all
from robotdesc.mesh.cache import summary_from_json, summary_to_json
from robotdesc.mesh.errors import MeshError, MeshErrorKind, MeshLimits
from robotdesc.mesh.records import MeshSummary

log = logging.getLogger(__name__)

__all__ = ["MIN_JOBS", "Job", "Prefetch", "Summarize"]

#: A file to summarize: (path, the `<mesh scale>` applied to it).
Job = tuple[str, tuple[float, ...]]
#: Summarizes one job (loads the file): the summary, or MeshError.
Summarize = Callable[[str, Sequence[float], MeshLimits], MeshSummary]

#: Fewer files than this are summarized here alone (a fork costs a few milliseconds).
MIN_JOBS = 4

#: Longest answer read from the child at once (a summary is well under a kilobyte).
_MAX_LINE = 1 << 20

#: Who claimed a job, in the shared page.
_FREE, _HERE, _CHILD = 0, 1, 2


class Prefetch:
    """The summaries of `jobs`, made by this process and a forked child together.

    Args:
        jobs: the files, in the order they will be asked for.
        limits: the size limits both processes read them with.
        summarize: what summarizes a file (`robotdesc.mesh.analyze`'s, without the cache).
    """

    def __init__(self, jobs: Sequence[Job], limits: MeshLimits, summarize: Summarize) -> None:
        self._jobs = list(jobs)
        self._index = {job: number for number, job in reversed(list(enumerate(jobs)))}
        self._limits = limits
        self._summarize = summarize
        self._answers: dict[int, MeshSummary | MeshError | None] = {}
        self._pending = b""
        self._child: Forked | None = None
        self._claims = mmap.mmap(-1, max(1, len(jobs)))  # shared with the child after fork
        self._largest_first = _by_size(self._jobs)
        #: jobs only the child takes: COLLADA files while pycollada is not imported here
        #: (its import is about 60 ms of CPU: made once, in the child)
        self._reserved = frozenset(
            number for number, (path, _) in enumerate(self._jobs)
            if path.lower().endswith(".dae") and "collada" not in sys.modules)
        try:
            self._child = Forked(self._serve)
            self._child.send(b"")  # no input: the jobs came with the fork
        except OSError as error:
            log.debug("mesh summaries not computed in a second process: %s", error)

    def take(self, path: str, scale: Sequence[float]) -> MeshSummary | MeshError | None:
        """The summary of a file (or why it cannot be used as a mesh); None when it is not
        one of the jobs, or the child failed on it: the caller summarizes it itself."""
        number = self._index.get((path, tuple(scale)))
        if number is None:
            return None
        if number not in self._answers and self._claim(number):
            self._answers[number] = self._here(number)
        while number not in self._answers and self._running():
            self._read(wait=False)
            if number in self._answers:
                break
            other = self._smallest_free()
            if other is None:
                self._read(wait=True)
            elif self._claim(other):
                self._answers[other] = self._here(other)
        return self._answers.pop(number, None)

    def close(self) -> None:
        """End the child (when it still runs) and reap it."""
        if self._child is not None:
            self._child.close()
            self._child = None

    def __del__(self) -> None:
        self.close()

    def _running(self) -> bool:
        return self._child is not None and self._child.running

    # --- this process -------------------------------------------------------------------

    def _claim(self, number: int) -> bool:
        """Claim a job for this process: False when the child has it (and still runs)."""
        if (self._claims[number] == _CHILD or number in self._reserved) and self._running():
            return False
        self._claims[number] = _HERE
        return True

    def _here(self, number: int) -> MeshSummary | MeshError | None:
        path, scale = self._jobs[number]
        try:
            return self._summarize(path, scale, self._limits)
        except MeshError as error:
            return error
        except Exception:  # noqa: BLE001 -- summarized again where it is asked for: raised there
            return None

    def _smallest_free(self) -> int | None:
        for number in reversed(self._largest_first):
            if self._claims[number] == _FREE and number not in self._answers \
                    and number not in self._reserved:
                return number
        return None

    def _read(self, wait: bool) -> None:
        """Take in the child's answers written so far (`wait`: at least one more)."""
        if self._child is None:
            return
        chunk = self._child.read(wait)
        if chunk is None:
            return
        if not chunk or len(self._pending) + len(chunk) > _MAX_LINE:
            self.close()  # the child ended (or wrote what it does not write)
            return
        *lines, self._pending = (self._pending + chunk).split(b"\n")
        for line in lines:
            self._record(line)

    def _record(self, line: bytes) -> None:
        try:
            record = json.loads(line)
            number = int(record["job"])
            if not 0 <= number < len(self._jobs):
                raise ValueError(f"no job {number}")
            if number in self._answers:
                return  # both summarized it: this process's is kept
            if "summary" in record:
                self._answers[number] = summary_from_json(record["summary"])
            elif "error" in record:
                self._answers[number] = MeshError(MeshErrorKind(record["error"]["kind"]),
                                                  str(record["error"]["detail"]),
                                                  self._jobs[number][0])
            else:  # the child failed on it: summarized where it is asked for
                self._answers[number] = None
        except (ValueError, KeyError, TypeError) as error:
            log.debug("mesh summaries of the second process: unreadable answer (%s)", error)
            self.close()

    # --- the child ----------------------------------------------------------------------

    def _serve(self, _inbox: int, out: int) -> None:
        """Summarize each free job, largest first, one JSON line each (runs in the child)."""
        reserved_first = sorted(self._reserved) + [
            number for number in self._largest_first if number not in self._reserved]
        for number in reserved_first:
            if self._claims[number] != _FREE:
                continue
            self._claims[number] = _CHILD
            path, scale = self._jobs[number]
            record: dict[str, object] = {"job": number}
            try:
                record["summary"] = summary_to_json(self._summarize(path, scale, self._limits))
            except MeshError as error:
                record["error"] = {"kind": error.kind.value, "detail": error.detail}
            except Exception:  # noqa: BLE001 -- summarized again by the parent
                record["failed"] = True
            write_all(out, (json.dumps(record, separators=(",", ":")) + "\n").encode())


def _by_size(jobs: Sequence[Job]) -> list[int]:
    """The jobs' numbers, the largest file first (the time to summarize a file grows with
    its size)."""
    sizes = []
    for number, (path, _) in enumerate(jobs):
        try:
            sizes.append((-os.path.getsize(path), number))
        except OSError:
            sizes.append((0, number))
    return [number for _, number in sorted(sizes)]
