"""Hostile xacro files against the OS confinement of the worker, through the command line.

Each attack is a `.urdf.xacro` inside a package that uses only `${...}` expressions: it climbs
from `xacro.tokenize` to the builtins (as tests/expansion/fixtures/bad_pkg/urdf/escape_os does)
and `exec`s a Python payload. With `disarm=True` the payload first switches off the in-process
audit guard (found through the closure of xacro's patched `parse`), so what holds is the
operating system alone: Landlock and seccomp. Every attack must end with exit 2 and leave no
trace: no file changed, created or removed, no connection, no process, no secret printed.
"""

from __future__ import annotations

import os
import secrets
import signal
import socket
import time
from pathlib import Path

import pytest

from expansion.attack import DISARMED, assert_refused, hostile, lint, robotdesc, snapshot
from robotdesc.expansion import confine

pytestmark = pytest.mark.skipif(not confine.probe().available,
                                reason="no Landlock/seccomp here: untrusted expansion is refused")

@pytest.fixture
def outside(tmp_path: Path) -> Path:
    """A folder beside the package, with a secret, a script and a file to destroy."""
    folder = tmp_path / "outside"
    folder.mkdir()
    (folder / "secret.txt").write_text("TOPSECRET-" + secrets.token_hex(8))
    (folder / "run.sh").write_text("#!/bin/sh\necho harmless\n")
    (folder / "keep.txt").write_text("keep me\n")
    return folder




def test_the_disarm_prelude_really_switches_the_guard_off(tmp_path):
    """Without this, the disarmed tests would prove nothing about the OS layer."""
    probe = tmp_path / "attack_pkg" / "urdf" / "inside.txt"
    payload = f"import gc\nprint('GC-REACHED', len(gc.get_objects()) > 0)\nopen({str(probe)!r}).close()\n"
    path = hostile(tmp_path, payload, disarm=True)
    probe.write_text("x")
    done = lint(path, tmp_path)
    assert "GC-REACHED True" in done.stderr, done.stderr  # refused by the guard when armed
    assert done.returncode in (0, 1), done.stdout + done.stderr


def test_gc_disarm_then_os_system(tmp_path, outside):
    """Issue 21, bypass 1: gc.get_objects() finds the guard, then os.system runs a shell."""
    marker = outside / "PWNED"
    payload = ("import gc, os\n"
               "for o in gc.get_objects():\n"
               "    if type(o).__name__ == 'Guard': o.armed = False\n"
               f"os.system('touch {marker}')\n")
    done = lint(hostile(tmp_path, payload, disarm=False), tmp_path)
    assert_refused(done)
    assert not marker.exists()


@DISARMED
def test_os_system_and_subprocess(tmp_path, outside, disarm):
    marker = outside / "PWNED"
    payload = (f"import os, subprocess\nos.system('touch {marker}')\n"
               f"subprocess.Popen(['/bin/sh', '-c', 'touch {marker}']).wait()\n")
    done = lint(hostile(tmp_path, payload, disarm=disarm), tmp_path)
    assert_refused(done)
    assert not marker.exists()
    if disarm:
        assert "sandbox" in done.stderr


@DISARMED
def test_posixsubprocess_fork_exec(tmp_path, outside, disarm):
    """Issue 21, bypass 2: _posixsubprocess.fork_exec raises no audit event."""
    marker = outside / "PWNED"
    payload = f"""
import _posixsubprocess, os
r, w = os.pipe()
_posixsubprocess.fork_exec([b'/bin/sh', b'-c', b'touch {marker}'], [b'/bin/sh'], True, (w,),
                           None, None, -1, -1, -1, -1, -1, -1, r, w, True, False, -1, None,
                           None, None, -1, None, False)
import time; time.sleep(0.5)
"""
    done = lint(hostile(tmp_path, payload, disarm=disarm), tmp_path)
    assert_refused(done)
    assert not marker.exists()


@DISARMED
def test_ctypes_libc_system(tmp_path, outside, disarm):
    marker = outside / "PWNED"
    payload = f"import ctypes\nctypes.CDLL(None).system(b'touch {marker}')\n"
    done = lint(hostile(tmp_path, payload, disarm=disarm), tmp_path)
    assert_refused(done)
    assert not marker.exists()


@DISARMED
def test_os_fork_and_a_detached_process(tmp_path, outside, disarm):
    """A double fork that would outlive robotdesc: refused at the first fork."""
    token = f"robotdesc-orphan-{secrets.token_hex(6)}"
    marker = outside / "PWNED"
    payload = f"""
import os, time
if os.fork() == 0:
    os.setsid()
    if os.fork() == 0:
        open({str(marker)!r}, 'w').close()
        os.execv('/bin/sleep', ['/bin/sleep', '30', {token!r}])
    os._exit(0)
time.sleep(0.2)
"""
    done = lint(hostile(tmp_path, payload, disarm=disarm), tmp_path)
    assert_refused(done)
    time.sleep(0.3)
    assert not marker.exists()
    assert not _processes_with(token)


@DISARMED
def test_socket_connect_to_a_local_listener(tmp_path, disarm):
    server = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    server.bind(("127.0.0.1", 0))
    server.listen(5)
    server.setblocking(False)
    port = server.getsockname()[1]
    payload = (f"import socket\ns = socket.create_connection(('127.0.0.1', {port}), timeout=2)\n"
               "s.sendall(b'leak')\n")
    try:
        done = lint(hostile(tmp_path, payload, disarm=disarm), tmp_path)
        assert_refused(done)
        with pytest.raises(BlockingIOError):
            server.accept()
    finally:
        server.close()


def _mmap_payload(target: Path) -> str:
    return (f"import mmap\nf = open({str(target)!r}, 'r+b')\n"
            "m = mmap.mmap(f.fileno(), 0)\nm[0:4] = b'EVIL'\nm.flush()\n")


@DISARMED
def test_mmap_rewrite_of_a_script(tmp_path, outside, disarm):
    """The 0-byte file-size limit only stops write(); a shared mapping must be refused too."""
    before = snapshot(outside)
    inside = tmp_path / "b" / "attack_pkg" / "urdf" / "inside.sh"
    cases = [hostile(tmp_path / "a", _mmap_payload(outside / "run.sh"), disarm=disarm),
             hostile(tmp_path / "b", _mmap_payload(inside), disarm=disarm)]
    inside.write_text("#!/bin/sh\necho inside\n")
    inside_before = snapshot(inside.parent)
    for path in cases:
        assert_refused(lint(path, tmp_path))
    assert snapshot(outside) == before
    assert snapshot(inside.parent) == inside_before


@DISARMED
def test_secret_file_and_parent_environment_never_leak(tmp_path, outside, disarm):
    secret_value = "ENVSECRET-" + secrets.token_hex(8)
    file_secret = (outside / "secret.txt").read_text()
    payload = f"""
import os
stolen = open({str(outside / 'secret.txt')!r}).read()
stolen += open('/proc/%d/environ' % os.getppid(), 'rb').read().decode('latin-1')
raise RuntimeError('LEAK ' + stolen)
"""
    done = lint(hostile(tmp_path, payload, disarm=disarm), tmp_path,
                env={"ROBOTDESC_TEST_SECRET": secret_value})
    assert_refused(done)
    output = done.stdout + done.stderr
    assert secret_value not in output
    assert file_secret not in output
    assert "LEAK" not in output


@DISARMED
def test_secret_never_reaches_the_expanded_urdf(tmp_path, outside, disarm):
    """The secret copied into an element name: the expansion must fail, not print it."""
    file_secret = (outside / "secret.txt").read_text()
    payload = f"""
import sys
data = open({str(outside / 'secret.txt')!r}).read()
sys.modules['xacro'].substitution_args_context['arg']['stolen'] = data
"""
    path = hostile(tmp_path, payload, disarm=disarm)
    path.write_text(path.read_text().replace("</robot>", '  <xacro:arg name="stolen" default="none"/>\n'
                                             '  <link name="$(arg stolen)"/>\n</robot>'))
    out = tmp_path / "out.urdf"
    done = robotdesc("expand", "--no-cache", str(path), "-o", str(out), cwd=tmp_path)
    assert_refused(done)
    assert file_secret not in done.stdout + done.stderr
    assert not out.exists() or file_secret not in out.read_text()


@DISARMED
def test_create_truncate_delete_outside_the_package(tmp_path, outside, disarm):
    before = snapshot(outside)
    payloads = [
        f"open({str(outside / 'created.txt')!r}, 'w').write('x')\n",
        f"import os\nos.truncate({str(outside / 'keep.txt')!r}, 0)\n",
        f"open({str(outside / 'keep.txt')!r}, 'r+').truncate(0)\n",
        f"import os\nos.remove({str(outside / 'keep.txt')!r})\n",
        f"import os\nos.rename({str(outside / 'keep.txt')!r}, {str(outside / 'moved.txt')!r})\n",
        f"import os\nos.mkdir({str(outside / 'newdir')!r})\n",
        f"import os\nos.symlink('/etc/passwd', {str(outside / 'link')!r})\n",
        f"import os\nos.chmod({str(outside / 'run.sh')!r}, 0o777)\n",
    ]
    for index, payload in enumerate(payloads):
        case = tmp_path / f"case{index}"
        case.mkdir()
        done = lint(hostile(case, payload, disarm=disarm), tmp_path)
        assert_refused(done)
    assert snapshot(outside) == before
    assert sorted(p.name for p in outside.iterdir()) == ["keep.txt", "run.sh", "secret.txt"]


@DISARMED
def test_no_write_inside_the_package_either(tmp_path, disarm):
    target = tmp_path / "attack_pkg" / "urdf" / "dropped.txt"
    done = lint(hostile(tmp_path, f"open({str(target)!r}, 'w').write('x')\n", disarm=disarm),
                tmp_path)
    assert_refused(done)
    assert not target.exists()


@DISARMED
def test_writing_through_an_inherited_descriptor(tmp_path, outside, disarm):
    """A descriptor robotdesc inherits is not handed on to the worker."""
    target = outside / "keep.txt"
    before = target.read_bytes()
    fd = os.open(target, os.O_WRONLY | os.O_APPEND)
    try:
        payload = f"import os\nos.write({fd}, b'EVIL')\n"
        done = lint(hostile(tmp_path, payload, disarm=disarm), tmp_path, pass_fds=(fd,))
    finally:
        os.close(fd)
    assert_refused(done, by_sandbox=False)  # EBADF: the worker never had the descriptor
    assert target.read_bytes() == before


@DISARMED
def test_a_forged_answer_on_the_worker_output_is_refused(tmp_path, outside, disarm):
    """The worker's stdout is its answer: a forged one naming outside files is refused."""
    payload = f"""
import json, os
answer = {{"ok": True, "xml": "<robot name='x'><link name='l'/></robot>",
          "files": [{str(outside / 'secret.txt')!r}], "files_read": [{str(outside / 'secret.txt')!r}],
          "packages": [], "macro_recursion": []}}
os.write(1, json.dumps(answer).encode())
os._exit(0)
"""
    done = lint(hostile(tmp_path, payload, disarm=disarm), tmp_path)
    assert_refused(done)
    assert (outside / "secret.txt").read_text() not in done.stdout + done.stderr


@DISARMED
def test_signalling_the_parent_is_refused(tmp_path, disarm):
    payload = "import os, signal\nos.kill(os.getppid(), signal.SIGTERM)\n"
    done = lint(hostile(tmp_path, payload, disarm=disarm), tmp_path)
    assert_refused(done)  # the parent lived to report it


def test_trusted_mode_is_not_confined(tmp_path):
    """--trusted lifts the sandbox for one's own files (a subprocess runs)."""
    marker = tmp_path / "TRUSTED_RAN"
    payload = f"import subprocess\nsubprocess.run(['/bin/sh', '-c', 'touch {marker}'])\n"
    done = robotdesc("lint", "--no-cache", "--trusted", str(hostile(tmp_path, payload, disarm=False)),
                     cwd=tmp_path)
    assert done.returncode in (0, 1), done.stdout + done.stderr
    assert marker.exists()


def _processes_with(token: str) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                if token.encode() in (entry / "cmdline").read_bytes():
                    found.append(int(entry.name))
            except OSError:
                continue
    for pid in found:  # never leave one behind, even when the test fails
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass
    return found
