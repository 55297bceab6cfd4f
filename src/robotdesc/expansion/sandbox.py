"""Limits and guards for the xacro worker process (POSIX).

A xacro file is code: `${}` and `$(eval)` run Python, and xacro's own name filter can be
bypassed. The worker therefore runs with resource limits (address space, CPU seconds, no file
writes), a cleaned environment chosen by the parent, and, in safe mode, an audit hook that
refuses process creation, sockets, native code, file writes and reads outside allowed roots.

The audit hook is the first line, the one that gives a good message with the file and line.
Python's audit hooks are no security boundary (code in the same process can switch them
off); the boundary is the operating system's confinement (`robotdesc.expansion.confine`).
Importing code (a .pyc read through `marshal`) from the code roots is therefore allowed:
what matters is what the OS lets the process do.
"""

from __future__ import annotations

import os
import sys
from dataclasses import dataclass, field

from robotdesc.trust import real_within

#: Audit events refused outright in safe mode (prefix match on the event name).
_FORBIDDEN_EVENTS = (
    "os.system", "os.exec", "os.posix_spawn", "os.spawn", "os.fork", "os.forkpty", "os.kill",
    "os.killpg", "subprocess.Popen", "socket.", "ctypes.", "os.remove", "os.rename", "os.rmdir",
    "os.mkdir", "os.chmod", "os.chown", "os.symlink", "os.link", "os.truncate", "os.putenv",
    "os.unsetenv", "os.chdir", "shutil.", "pty.", "webbrowser.", "urllib.", "http.", "ftplib.",
    "smtplib.", "sys.setrecursionlimit", "pickle.find_class", "sqlite3.", "gc.get_objects",
    "gc.get_referrers", "gc.get_referents", "sys._current_frames", "mmap.",
)
#: Audit events an expansion raises thousands of times (xacro compiles and evaluates every
#: expression) that safe mode never refuses: let through before the prefix test.
_FREQUENT_EVENTS = frozenset({"compile", "exec", "builtins.id"})
_WRITE_FLAGS = os.O_WRONLY | os.O_RDWR | os.O_APPEND | os.O_CREAT | os.O_TRUNC


class Forbidden(Exception):
    """Raised inside the worker when safe mode refuses an operation."""


def apply_limits(memory_mb: int, cpu_seconds: int) -> None:
    """Cap this process: address space (MiB), CPU time (s), no files written, no core dumps."""
    import resource

    def cap(kind: int, value: int) -> None:
        soft, hard = resource.getrlimit(kind)
        if hard != resource.RLIM_INFINITY:
            value = min(value, hard)
        resource.setrlimit(kind, (value, value if hard == resource.RLIM_INFINITY else hard))

    cap(resource.RLIMIT_AS, memory_mb * 1024 * 1024)
    cap(resource.RLIMIT_CPU, cpu_seconds)
    cap(resource.RLIMIT_FSIZE, 0)
    cap(resource.RLIMIT_CORE, 0)


def _real(path: str) -> str:
    return os.path.realpath(path)


def is_within(path: str, roots: tuple[str, ...] | list[str]) -> bool:
    """True when the real path of `path` lies inside one of the (real) `roots` (never raises:
    see `robotdesc.trust.real_within`)."""
    return real_within(path, roots)


@dataclass
class Guard:
    """The worker's audit hook state.

    Attributes:
        safe: refuse forbidden operations (False in --trusted mode: only record).
        data_roots: folders whose files a description may read (packages in use).
        code_roots: folders Python may import from (the interpreter and site-packages).
        files_read: data files opened so far (absolute real paths, in order).
    """

    safe: bool
    data_roots: list[str] = field(default_factory=list)
    code_roots: tuple[str, ...] = ()
    files_read: list[str] = field(default_factory=list)
    armed: bool = False

    def allow_root(self, folder: str) -> None:
        real = _real(folder)
        if real not in self.data_roots:
            self.data_roots.append(real)

    def __call__(self, event: str, args: tuple[object, ...]) -> None:
        if not self.armed or event in _FREQUENT_EVENTS:
            return
        if event == "open":
            self._check_open(args)
        elif self.safe and event.startswith(_FORBIDDEN_EVENTS):
            raise Forbidden(f"safe mode refuses '{event}' (a xacro expression tried to reach "
                            f"the operating system); use --trusted only for files you trust")

    def _check_open(self, args: tuple[object, ...]) -> None:
        path, mode, flags = (list(args) + [None, None, None])[:3]
        if not isinstance(path, (str, bytes, os.PathLike)):
            return  # an already open file descriptor
        path = os.fsdecode(path)
        writing = (isinstance(mode, str) and any(c in mode for c in "wax+")) or \
                  (isinstance(flags, int) and flags & _WRITE_FLAGS)
        if self.safe and writing:
            raise Forbidden(f"safe mode refuses to write '{path}'")
        if is_within(path, self.data_roots):
            real = _real(path)
            if real not in self.files_read and not real.endswith((".py", ".pyc")):
                self.files_read.append(real)
            return
        if not self.safe or is_within(path, self.code_roots):
            return
        raise Forbidden(f"safe mode refuses to read '{path}': it lies outside the packages in use "
                        f"({', '.join(self.data_roots)})")




def install(guard: Guard) -> None:
    """Install the audit hook (it cannot be removed for the life of the process)."""
    sys.addaudithook(guard)
