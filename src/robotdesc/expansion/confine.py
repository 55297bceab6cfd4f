"""OS-level confinement of the xacro worker (Linux): the boundary the audit guard is not.

Applied inside the worker process, after everything it needs is imported and before any
xacro expression runs, in this order:

1. `no_new_privs`, and every capability dropped (bounding, ambient, effective, permitted,
   inheritable) when the worker runs with any (as root in CI);
2. Landlock (the kernel's syscalls, through ctypes): every filesystem right the running ABI
   knows is handled, and only reading files and listing folders is granted, beneath the data
   roots (the packages the resolver can return, the top file's package or folder) and the
   code roots (the Python installation's library folders, robotdesc's own folder). No write,
   create, remove, truncate or device ioctl anywhere; with ABI 4 no TCP bind/connect; with
   ABI 6 no abstract unix sockets and no signals outside the worker;
3. seccomp-bpf (libseccomp through pyseccomp): system calls that have no use in an expansion
   (process creation, sockets, ptrace, mounts, file attribute changes, signals to other
   processes, ...) end the worker at once (SIGSYS; the parent reports a sandbox violation).
   `clone3` answers ENOSYS so that the C library falls back to `clone`, which is allowed for
   threads only.

`probe()` tells, in the parent, whether all of this is available; robotdesc refuses untrusted
expansion where it is not (see docs/security.md).
"""

from __future__ import annotations

import ctypes
import errno
import functools
import logging
import os
import sys
import sysconfig
from collections.abc import Iterable
from dataclasses import dataclass
from types import ModuleType

log = logging.getLogger(__name__)

# --- Landlock (include/uapi/linux/landlock.h) ---------------------------------------------
_SYS_LANDLOCK_CREATE_RULESET = 444  # the same number on x86_64, aarch64 and the other
_SYS_LANDLOCK_ADD_RULE = 445        # architectures that use the generic syscall table
_SYS_LANDLOCK_RESTRICT_SELF = 446
_LANDLOCK_CREATE_RULESET_VERSION = 1
_LANDLOCK_RULE_PATH_BENEATH = 1

FS_EXECUTE = 1 << 0
FS_WRITE_FILE = 1 << 1
FS_READ_FILE = 1 << 2
FS_READ_DIR = 1 << 3
FS_REMOVE_DIR = 1 << 4
FS_REMOVE_FILE = 1 << 5
FS_MAKE_CHAR = 1 << 6
FS_MAKE_DIR = 1 << 7
FS_MAKE_REG = 1 << 8
FS_MAKE_SOCK = 1 << 9
FS_MAKE_FIFO = 1 << 10
FS_MAKE_BLOCK = 1 << 11
FS_MAKE_SYM = 1 << 12
FS_REFER = 1 << 13      # ABI 2
FS_TRUNCATE = 1 << 14   # ABI 3
FS_IOCTL_DEV = 1 << 15  # ABI 5
NET_BIND_TCP = 1 << 0     # ABI 4
NET_CONNECT_TCP = 1 << 1  # ABI 4
SCOPE_ABSTRACT_UNIX_SOCKET = 1 << 0  # ABI 6
SCOPE_SIGNAL = 1 << 1                # ABI 6

#: The filesystem rights each ABI knows (all of them are handled, i.e. denied unless granted).
_FS_RIGHTS_BY_ABI = {1: (1 << 13) - 1, 2: (1 << 14) - 1, 3: (1 << 15) - 1, 4: (1 << 15) - 1,
                     5: (1 << 16) - 1}
_READ = FS_READ_FILE | FS_READ_DIR

# --- prctl and capabilities ---------------------------------------------------------------
_PR_CAPBSET_DROP = 24
_PR_GET_SECCOMP = 21
_PR_SET_NO_NEW_PRIVS = 38
_PR_GET_NO_NEW_PRIVS = 39
_PR_CAP_AMBIENT = 47
_PR_CAP_AMBIENT_CLEAR_ALL = 4
_CAP_VERSION_3 = 0x20080522
_CAP_LAST_FALLBACK = 63

# --- seccomp ------------------------------------------------------------------------------
_CLONE_THREAD = 0x00010000
_TIOCSTI = 0x5412
_TIOCLINUX = 0x541C
_U32 = 0xFFFFFFFF

#: System calls that end the worker whatever their arguments (names the running
#: architecture does not have are skipped).
DENIED_SYSCALLS = (
    # new programs and processes (threads are clone with CLONE_THREAD, handled apart)
    "execve", "execveat", "fork", "vfork",
    # network and local sockets
    "socket", "socketpair", "connect", "bind", "listen", "accept", "accept4",
    # other processes
    "ptrace", "process_vm_readv", "process_vm_writev", "tkill", "pidfd_open",
    "pidfd_send_signal", "pidfd_getfd", "kcmp", "process_madvise",
    # asynchronous I/O that bypasses seccomp's view of system calls
    "io_uring_setup", "io_uring_enter", "io_uring_register",
    # namespaces and mounts
    "mount", "umount2", "pivot_root", "chroot", "unshare", "setns", "open_tree", "move_mount",
    "fsopen", "fsmount", "fspick", "fsconfig", "mount_setattr",
    # file handles, attributes, links and special files
    "open_by_handle_at", "name_to_handle_at", "chmod", "fchmod", "fchmodat", "fchmodat2",
    "chown", "fchown", "lchown", "fchownat", "setxattr", "lsetxattr", "fsetxattr",
    "setxattrat", "removexattr", "lremovexattr", "fremovexattr", "removexattrat", "utime",
    "utimes", "futimesat", "utimensat", "mknod", "mknodat", "link", "linkat", "symlink",
    "symlinkat", "truncate",
    # the kernel itself
    "bpf", "perf_event_open", "userfaultfd", "keyctl", "add_key", "request_key",
    "personality", "kexec_load", "kexec_file_load", "init_module", "finit_module",
    "delete_module", "reboot", "swapon", "swapoff", "sethostname", "setdomainname",
    "settimeofday", "clock_settime", "clock_adjtime", "adjtimex", "acct", "quotactl",
    "quotactl_fd", "iopl", "ioperm", "syslog", "fanotify_init", "lookup_dcookie", "vhangup",
)
#: Signals allowed only to the worker itself: (name, index of the process argument, which
#: must equal the worker's pid).
_SIGNAL_SELF_ONLY = (("kill", 0), ("tgkill", 0), ("rt_sigqueueinfo", 0),
                     ("rt_tgsigqueueinfo", 0))
#: Calls that may name another process, allowed only with 0 ("this process").
_ZERO_SELF_ONLY = (("prlimit64", 0), ("setpriority", 1), ("getpriority", 1),
                   ("ioprio_set", 1), ("ioprio_get", 1), ("sched_setaffinity", 0),
                   ("sched_setscheduler", 0), ("sched_setparam", 0), ("sched_setattr", 0),
                   ("sched_getaffinity", 0), ("sched_getscheduler", 0), ("sched_getparam", 0),
                   ("sched_getattr", 0), ("sched_rr_get_interval", 0), ("get_robust_list", 0),
                   ("migrate_pages", 0), ("move_pages", 0), ("setpgid", 0), ("setpgid", 1),
                   ("getpgid", 0), ("getsid", 0))
#: Calls whose "which" argument says what the "who" means: only a single process is allowed
#: (PRIO_PROCESS = 0, IOPRIO_WHO_PROCESS = 1); a process group or a whole user is not, even
#: with who = 0 (`setpriority(PRIO_USER, 0, 19)` renices every process of the user).
_WHICH_PROCESS_ONLY = (("setpriority", 0, 0), ("getpriority", 0, 0), ("ioprio_set", 0, 1),
                       ("ioprio_get", 0, 1))


class ConfinementError(Exception):
    """The worker could not be confined (the expansion must not go on)."""


@dataclass(frozen=True)
class Support:
    """Whether this system can confine the worker.

    Attributes:
        available: Landlock and seccomp (with libseccomp) can both be used.
        reason: why not, in a user's words ("" when available).
        landlock_abi: the kernel's Landlock ABI version (0 when absent).
    """

    available: bool
    reason: str = ""
    landlock_abi: int = 0


_libc = ctypes.CDLL(None, use_errno=True) if sys.platform.startswith("linux") else None


def _lib() -> ctypes.CDLL:
    """The C library (Linux only; the callers run there)."""
    if _libc is None:
        raise ConfinementError("no C library to confine with (not Linux)")
    return _libc


def _syscall(number: int, *args: object) -> int:
    result = int(_lib().syscall(ctypes.c_long(number), *args))
    if result < 0:
        code = ctypes.get_errno()
        raise OSError(code, os.strerror(code))
    return result


def landlock_abi() -> int:
    """The Landlock ABI version of the running kernel (0: no Landlock)."""
    if _libc is None:
        return 0
    try:
        return _syscall(_SYS_LANDLOCK_CREATE_RULESET, None, ctypes.c_size_t(0),
                        ctypes.c_uint32(_LANDLOCK_CREATE_RULESET_VERSION))
    except OSError:  # ENOSYS (old kernel), EOPNOTSUPP (disabled at boot), EPERM (container)
        return 0


def _load_pyseccomp() -> ModuleType:
    try:
        import pyseccomp
    except (ImportError, OSError, AttributeError) as exc:  # not installed, or no libseccomp.so
        raise ConfinementError(f"libseccomp is not usable ({exc})") from exc
    module: ModuleType = pyseccomp
    return module


@functools.lru_cache(maxsize=1)
def probe() -> Support:
    """Whether the worker can be confined here (cached for the process)."""
    if not sys.platform.startswith("linux"):
        return Support(False, f"the xacro worker can only be confined on Linux (this is {sys.platform})")
    abi = landlock_abi()
    if abi < 1:
        return Support(False, "the kernel has no Landlock (Linux 5.13 or newer with Landlock "
                              "enabled is needed)")
    if _lib().prctl(_PR_GET_SECCOMP, 0, 0, 0, 0) < 0:
        return Support(False, "the kernel has no seccomp filters", abi)
    try:
        pyseccomp = _load_pyseccomp()
        pyseccomp.SyscallFilter(pyseccomp.ALLOW)
    except (ConfinementError, OSError) as exc:
        return Support(False, str(exc), abi)
    return Support(True, "", abi)


#: Folders never granted whole as code roots, even when a path setting names them.
_TOO_WIDE = frozenset({"/", "/usr", "/usr/local", "/opt", "/home", "/root", "/tmp", "/etc",
                       "/var", "/proc", "/sys", "/dev", os.path.expanduser("~")})


def code_roots() -> tuple[str, ...]:
    """Concrete folders (and zip files) Python code is imported from; never a whole prefix."""
    paths = sysconfig.get_paths()
    candidates = [paths.get(key) for key in ("stdlib", "platstdlib", "purelib", "platlib")]
    candidates += [p for p in sys.path
                   if p and os.path.isabs(p) and ("site-packages" in p or "dist-packages" in p
                                                  or os.path.isfile(p))]
    candidates.append(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # robotdesc/
    for name in ("xacro", "yaml", "lxml"):
        module = sys.modules.get(name)
        file = getattr(module, "__file__", None) if module is not None else None
        if file:
            candidates.append(os.path.dirname(os.path.abspath(file)))
    roots: list[str] = []
    for candidate in candidates:
        if candidate and os.path.exists(candidate):
            real = os.path.realpath(candidate)
            if real not in roots and real not in _TOO_WIDE:
                roots.append(real)
    return tuple(roots)



# --- applying -----------------------------------------------------------------------------


class _RulesetAttr(ctypes.Structure):
    _fields_ = [("handled_access_fs", ctypes.c_uint64), ("handled_access_net", ctypes.c_uint64),
                ("scoped", ctypes.c_uint64)]


class _PathBeneathAttr(ctypes.Structure):
    _pack_ = 1
    _fields_ = [("allowed_access", ctypes.c_uint64), ("parent_fd", ctypes.c_int32)]


class _CapHeader(ctypes.Structure):
    _fields_ = [("version", ctypes.c_uint32), ("pid", ctypes.c_int)]


class _CapData(ctypes.Structure):
    _fields_ = [("effective", ctypes.c_uint32), ("permitted", ctypes.c_uint32),
                ("inheritable", ctypes.c_uint32)]


def _prctl(option: int, arg: int = 0) -> int:
    result = int(_lib().prctl(option, ctypes.c_ulong(arg), 0, 0, 0))
    if result < 0:
        code = ctypes.get_errno()
        raise OSError(code, os.strerror(code))
    return result


def _capabilities() -> tuple[int, int]:
    header = _CapHeader(_CAP_VERSION_3, 0)
    data = (_CapData * 2)()
    if _lib().capget(ctypes.byref(header), data) < 0:
        code = ctypes.get_errno()
        raise OSError(code, os.strerror(code))
    effective = data[0].effective | (data[1].effective << 32)
    permitted = data[0].permitted | (data[1].permitted << 32)
    return effective, permitted


def drop_privileges() -> None:
    """Set no_new_privs and drop every capability the process holds."""
    _prctl(_PR_SET_NO_NEW_PRIVS, 1)
    effective, permitted = _capabilities()
    if effective or permitted:
        for cap in range(_CAP_LAST_FALLBACK + 1):
            try:
                _prctl(_PR_CAPBSET_DROP, cap)
            except OSError as exc:
                if exc.errno == errno.EINVAL:  # past the kernel's last capability
                    break
                raise
        _lib().prctl(_PR_CAP_AMBIENT, _PR_CAP_AMBIENT_CLEAR_ALL, 0, 0, 0)  # EINVAL before 4.3
        header = _CapHeader(_CAP_VERSION_3, 0)
        data = (_CapData * 2)()
        if _lib().capset(ctypes.byref(header), data) < 0:
            code = ctypes.get_errno()
            raise OSError(code, os.strerror(code))
    if _capabilities() != (0, 0) or _prctl(_PR_GET_NO_NEW_PRIVS) != 1:
        raise ConfinementError("capabilities could not be dropped")


def restrict_filesystem(read_roots: Iterable[str], abi: int) -> None:
    """Landlock: reading beneath `read_roots` only; nothing else on any filesystem or port."""
    fs = _FS_RIGHTS_BY_ABI[min(abi, max(_FS_RIGHTS_BY_ABI))]
    attr = _RulesetAttr(fs, 0, 0)
    size = 8
    if abi >= 4:
        attr.handled_access_net = NET_BIND_TCP | NET_CONNECT_TCP
        size = 16
    if abi >= 6:
        attr.scoped = SCOPE_ABSTRACT_UNIX_SOCKET | SCOPE_SIGNAL
        size = 24
    ruleset = _syscall(_SYS_LANDLOCK_CREATE_RULESET, ctypes.byref(attr), ctypes.c_size_t(size),
                       ctypes.c_uint32(0))
    try:
        for root in dict.fromkeys(read_roots):
            try:
                fd = os.open(root, os.O_PATH | os.O_CLOEXEC)
            except OSError as exc:
                log.debug("landlock: skipping %s (%s)", root, exc)
                continue
            try:
                access = _READ if os.path.isdir(root) else FS_READ_FILE
                rule = _PathBeneathAttr(access, fd)
                _syscall(_SYS_LANDLOCK_ADD_RULE, ctypes.c_int(ruleset),
                         ctypes.c_int(_LANDLOCK_RULE_PATH_BENEATH), ctypes.byref(rule),
                         ctypes.c_uint32(0))
            finally:
                os.close(fd)
        _syscall(_SYS_LANDLOCK_RESTRICT_SELF, ctypes.c_int(ruleset), ctypes.c_uint32(0))
    finally:
        os.close(ruleset)


def restrict_syscalls(pid: int) -> None:
    """seccomp-bpf: end the process on any system call an expansion has no use for."""
    sc = _load_pyseccomp()
    kill = sc.KILL_PROCESS
    rules = sc.SyscallFilter(sc.ALLOW)
    rules.set_attr(sc.Attr.ACT_BADARCH, kill)  # other ABIs (int 0x80, x32) are not allowed
    rules.set_attr(sc.Attr.CTL_TSYNC, 1)

    def add(action: int, name: str, *args: object) -> None:
        if sc.resolve_syscall(sc.Arch.NATIVE, name) < 0:
            return  # not a system call on this architecture
        rules.add_rule(action, name, *args)

    for name in DENIED_SYSCALLS:
        add(kill, name)
    add(kill, "clone", sc.Arg(0, sc.MASKED_EQ, _CLONE_THREAD, 0))
    add(sc.ERRNO(errno.ENOSYS), "clone3")  # its flags cannot be inspected: glibc falls back
    for request in (_TIOCSTI, _TIOCLINUX):
        add(kill, "ioctl", sc.Arg(1, sc.MASKED_EQ, _U32, request))
    for name, index in _SIGNAL_SELF_ONLY:
        add(kill, name, sc.Arg(index, sc.NE, pid))
    for name, index in _ZERO_SELF_ONLY:
        add(kill, name, sc.Arg(index, sc.NE, 0))
    for name, index, single in _WHICH_PROCESS_ONLY:
        add(kill, name, sc.Arg(index, sc.NE, single))
    rules.load()


def confine(data_roots: Iterable[str], code_roots_: Iterable[str]) -> None:
    """Confine the calling process for good (call it with no other thread running).

    Raises:
        ConfinementError: a layer could not be applied; the process must not run xacro.
    """
    support = probe()
    if not support.available:
        raise ConfinementError(support.reason)
    try:
        drop_privileges()
        restrict_filesystem([*data_roots, *code_roots_], support.landlock_abi)
        restrict_syscalls(os.getpid())
    except OSError as exc:
        raise ConfinementError(f"confinement failed: {exc}") from exc
