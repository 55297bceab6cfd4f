"""Attacks around the sandbox, through the unconfined parent (issue 28).

The worker is confined; the parent is not. These attacks, written as a pull request to a
description repository that CI lints would be, try to make the parent read or print what the
worker could not: a forged answer, a config in the scanned repository, a top file in the
home folder, a symlink in the tree, a poisoned cache, a syscall that reaches other processes,
floods of output, and a worker left running when the parent is ended. Each one must end with
exit 2 (or 0/1 where the file is harmless), and no canary (a random token in a file under a
throwaway HOME and in an environment variable) may appear in any output.
"""

from __future__ import annotations

import json
import os
import platform
import secrets
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from expansion.attack import DISARMED, SRC, assert_refused, hostile, package, robotdesc, snapshot
from robotdesc.expansion import ExpandOptions, cache, confine, expand_file, runner

pytestmark = pytest.mark.skipif(not confine.probe().available,
                                reason="no Landlock/seccomp here: untrusted expansion is refused")


class Canary:
    """A throwaway HOME with a secret key, and the same token in an environment variable."""

    def __init__(self, root: Path) -> None:
        self.token = "CANARY-" + secrets.token_hex(12)
        self.home = root / "home"
        (self.home / ".ssh").mkdir(parents=True)
        self.key = self.home / ".ssh" / "id_test"
        self.key.write_text(f"-----BEGIN KEY-----\n{self.token}\n{self.token}\n")
        self.repo = self.home / "repo"
        (self.repo / ".git").mkdir(parents=True)
        self.before = snapshot(self.home)

    def env(self) -> dict[str, str]:
        return {"HOME": str(self.home), "ROBOTDESC_CANARY": self.token,
                "ROBOTDESC_CACHE_DIR": str(self.home.parent / "cache"),
                "XDG_STATE_HOME": str(self.home.parent / "state")}

    def run(self, *args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
        return robotdesc(*args, cwd=cwd or self.repo, env=self.env())

    def assert_silent(self, done: subprocess.CompletedProcess) -> None:
        """No canary in any output, nothing changed under HOME but the repository."""
        output = done.stdout + done.stderr
        assert self.token not in output, output
        assert "Traceback" not in output, output
        after = {p: v for p, v in snapshot(self.home).items()
                 if not p.startswith(str(self.repo))}
        assert after == {p: v for p, v in self.before.items()
                         if not p.startswith(str(self.repo))}


@pytest.fixture
def canary(tmp_path: Path) -> Canary:
    return Canary(tmp_path)


def forged(answer: dict[str, object]) -> str:
    """A payload that writes `answer` as the worker's answer and exits."""
    return (f"import json, os\nos.write(1, json.dumps({answer!r}).encode())\nos._exit(0)\n")


ROBOT = "<robot name='x'><link name='l'/></robot>"


# 1. a forged answer steers the parent ---------------------------------------------------


@DISARMED
def test_forged_failure_spans_naming_a_secret_are_refused(canary, disarm):
    key = str(canary.key)
    path = hostile(canary.repo, forged({
        "ok": False, "kind": "ExpansionError", "message": "look here",
        "span": [key, 2, 1], "call_stack": [[key, 3, 1]]}), disarm=disarm)
    for command in ("lint", "expand"):
        done = canary.run(command, "--no-cache", str(path))
        assert_refused(done)
        assert "invalid answer" in done.stderr
        canary.assert_silent(done)


@DISARMED
def test_forged_success_spans_naming_a_secret_are_refused(canary, disarm):
    key = str(canary.key)
    top = str(canary.repo / "attack_pkg" / "urdf" / "attack.urdf.xacro")
    path = hostile(canary.repo, forged({
        "ok": True, "xml": ROBOT, "files": [top], "files_read": [top], "packages": [],
        "macro_recursion": [["m", 9, [key, 2, 1], [key, 3, 1]]],
        "declared_args": [["a", [key, 2, 1]]], "read_args": [],
        "env_defaults": [["HOME", "x", [key, 3, 1]]]}), disarm=disarm)
    done = canary.run("lint", "--no-cache", str(path))
    assert_refused(done)
    canary.assert_silent(done)


def test_a_span_through_a_symlink_in_the_package_is_refused(canary):
    package_dir = canary.repo / "attack_pkg"
    path = hostile(canary.repo, forged({
        "ok": False, "kind": "XmlSyntaxError", "message": "bad",
        "span": [str(package_dir / "urdf" / "inner.xacro"), 2, 1], "call_stack": []}),
        disarm=True)
    (package_dir / "urdf" / "inner.xacro").symlink_to(canary.key)
    done = canary.run("lint", "--no-cache", str(path))
    assert_refused(done)
    canary.assert_silent(done)


@DISARMED
def test_a_forged_internal_error_is_the_inputs_failure(canary, disarm):
    path = hostile(canary.repo, forged({"ok": False, "kind": "InternalError",
                                        "message": "boom", "span": None, "call_stack": []}),
                   disarm=disarm)
    done = canary.run("lint", "--no-cache", str(path))
    assert_refused(done, by_sandbox=False)
    assert "bug in robotdesc" not in done.stderr
    canary.assert_silent(done)


@pytest.mark.parametrize("answer", [
    {"ok": True, "xml": ROBOT},                                  # fields missing
    {"ok": True, "xml": 5, "files": [], "files_read": [], "packages": [],
     "macro_recursion": []},                                     # wrong type
    {"ok": False, "kind": "NoSuchKind", "message": "x"},         # unknown kind
    {"ok": False, "kind": "ExpansionError", "message": "x", "span": ["/etc/passwd", "1", 1]},
    [1, 2, 3],                                                   # not an object
], ids=["missing", "type", "kind", "span-type", "list"])
def test_malformed_answers_are_refused(canary, answer):
    done = canary.run("lint", "--no-cache", str(hostile(canary.repo, forged(answer),
                                                          disarm=True)))
    assert_refused(done)
    canary.assert_silent(done)


# 2. the scanned repository widens the jail -----------------------------------------------


def _load_yaml_package(repo: Path, expression: str) -> Path:
    top = package(repo, "robot_pkg") / "urdf" / "robot.urdf.xacro"
    top.write_text(f"""<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="${{{expression}}}"/>
</robot>
""")
    return top


@pytest.mark.parametrize("folder", ["~", "/", "..", "~/.ssh"])
def test_a_config_in_the_repository_cannot_grant_folders_outside_it(canary, folder):
    (canary.repo / "robotdesc.toml").write_text(f'[packages]\nevil = "{folder}"\n')
    top = _load_yaml_package(canary.repo,
                             "str(xacro.load_yaml('$(find evil)/.ssh/id_test'))")
    for command in (("expand", str(top)), ("lint", "--no-cache", str(top)),
                    ("lint", "--no-cache", ".")):
        done = canary.run(*command)
        assert done.returncode == 2, done.stdout + done.stderr
        assert "robotdesc.toml:2" in done.stderr and "outside the repository" in done.stderr
        canary.assert_silent(done)


def test_the_users_own_config_may_name_any_folder(canary, tmp_path):
    shared = tmp_path / "shared"
    shared.mkdir()
    (shared / "params.yaml").write_text("name: base\n")
    own = tmp_path / "own.toml"
    own.write_text(f'[packages]\nshared = "{shared}"\n')
    top = _load_yaml_package(canary.repo,
                             "xacro.load_yaml('$(find shared)/params.yaml')['name']")
    done = canary.run("expand", "--config", str(own), str(top))
    assert done.returncode == 0, done.stderr
    assert 'name="base"' in done.stdout


def test_a_config_in_the_repository_may_name_its_own_folders(canary):
    (canary.repo / "vendor").mkdir()
    (canary.repo / "vendor" / "params.yaml").write_text("name: base\n")
    (canary.repo / "robotdesc.toml").write_text('[packages]\nvendor = "vendor"\n')
    top = _load_yaml_package(canary.repo,
                             "xacro.load_yaml('$(find vendor)/params.yaml')['name']")
    done = canary.run("expand", str(top))
    assert done.returncode == 0, done.stderr
    assert 'name="base"' in done.stdout


# 3. a top file without a package ---------------------------------------------------------


def test_a_top_file_in_the_home_folder_reads_nothing_else(canary):
    top = canary.home / "robot.urdf.xacro"
    top.write_text("""<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="${str(xacro.load_yaml('.ssh/id_test'))}"/>
</robot>
""")
    canary.before = snapshot(canary.home)
    done = canary.run("expand", "--no-cache", str(top), cwd=canary.home)
    assert_refused(done)
    canary.assert_silent(done)


def test_a_loose_top_file_reads_visible_neighbours_but_not_hidden_ones(canary, tmp_path):
    loose = tmp_path / "download"
    (loose / ".secrets").mkdir(parents=True)
    (loose / ".secrets" / "token").write_text(f"t: {canary.token}\n")
    (loose / "params.yaml").write_text("name: base\n")
    top = loose / "robot.urdf.xacro"
    top.write_text("""<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="${xacro.load_yaml('params.yaml')['name']}"/>
</robot>
""")
    done = canary.run("expand", "--no-cache", str(top), cwd=loose)
    assert done.returncode == 0, done.stderr
    top.write_text(top.read_text().replace("params.yaml')['name']", ".secrets/token')['t']"))
    done = canary.run("expand", "--no-cache", str(top), cwd=loose)
    assert_refused(done)
    canary.assert_silent(done)


# 4. symlinks in the scanned tree ---------------------------------------------------------


def test_lint_of_a_folder_never_reads_a_symlink_out_of_it(canary):
    urdf = canary.repo / "urdf"
    urdf.mkdir()
    (urdf / "key.urdf").symlink_to(canary.key)
    (urdf / "robot.urdf").write_text(ROBOT)
    done = canary.run("lint", "--no-cache", ".")
    assert done.returncode == 2, done.stdout + done.stderr
    assert "key.urdf" in done.stderr and "symlink" in done.stderr
    canary.assert_silent(done)


def test_a_config_file_that_is_a_symlink_out_of_the_repository_is_refused(canary):
    (canary.home / "evil.toml").write_text(f'[packages]\nx = "{canary.home}"\n')
    (canary.repo / "robotdesc.toml").symlink_to(canary.home / "evil.toml")
    canary.before = snapshot(canary.home)
    top = _load_yaml_package(canary.repo, "'base'")
    done = canary.run("lint", "--no-cache", str(top))
    assert done.returncode == 2
    assert "symlink" in done.stderr
    canary.assert_silent(done)


# 5. cache poisoning -------------------------------------------------------------------


def test_a_forged_answer_with_no_inputs_cannot_answer_for_another_file(canary):
    path = hostile(canary.repo, forged({"ok": True, "xml": ROBOT, "files": [],
                                        "files_read": [], "packages": [],
                                        "macro_recursion": []}), disarm=True)
    first = canary.run("lint", str(path))
    assert first.returncode == 0, first.stdout + first.stderr
    path.write_text("""<?xml version="1.0"?>
<robot name="x"><link name="a"/><link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/></joint>
</robot>
""")
    second = canary.run("lint", str(path))
    fresh = canary.run("lint", "--no-cache", str(path))
    assert fresh.returncode == 1
    assert second.returncode == fresh.returncode, second.stdout


def _stored_entry(tmp_path: Path) -> tuple[Path, Path]:
    top = _load_yaml_package(tmp_path / "repo", "'base'")
    expand_file(top, options=ExpandOptions(cache_dir=str(tmp_path / "cache")))
    (entry,) = (tmp_path / "cache" / "expand").rglob("*.json")
    return top, entry


@pytest.mark.parametrize("tamper", ["no-inputs", "foreign-file", "foreign-span", "garbage"])
def test_a_planted_cache_entry_is_a_miss(tmp_path, tamper, monkeypatch):
    secret = tmp_path / "secret.txt"
    secret.write_text("TOPSECRET\n")
    top, entry = _stored_entry(tmp_path)
    record = json.loads(entry.read_bytes().split(b"\n", 1)[1])  # after the seal
    if tamper == "no-inputs":
        record["inputs"] = {}
    elif tamper == "foreign-file":
        record["inputs"][str(secret)] = cache.file_digest(str(secret))
        record["expanded"]["files_read"].append(str(secret))
    elif tamper == "foreign-span":
        record["expanded"]["declared_args"] = [["a", {"path": str(secret), "line": 1,
                                                       "col": 0}]]
    entry.write_text("[not json" if tamper == "garbage" else json.dumps(record))
    calls = []
    real = runner.run_worker
    monkeypatch.setattr(runner, "run_worker", lambda *a, **k: calls.append(1) or real(*a, **k))
    expanded = expand_file(top, options=ExpandOptions(cache_dir=str(tmp_path / "cache")))
    assert calls == [1]  # the entry was not believed: the worker ran again
    assert str(secret) not in expanded.files_read


# 6. system calls that address more than the worker ---------------------------------------


@pytest.mark.parametrize("call", ["setpriority-user", "setpriority-pgrp", "getpriority-user",
                                  "ioprio-user"])
def test_calls_addressing_a_user_or_group_end_the_worker(tmp_path, call):
    if call == "ioprio-user" and platform.machine() != "x86_64":
        pytest.skip("the ioprio_set number used here is x86_64's")
    payload = {
        "setpriority-user": "import os\nos.setpriority(os.PRIO_USER, 0, 19)\n",
        "setpriority-pgrp": "import os\nos.setpriority(os.PRIO_PGRP, 0, 19)\n",
        "getpriority-user": "import os\nos.getpriority(os.PRIO_USER, 0)\n",
        "ioprio-user": "import ctypes\nctypes.CDLL(None).syscall(251, 3, 0, (3 << 13) | 7)\n",
    }[call]
    before = os.getpriority(os.PRIO_PROCESS, 0)
    done = robotdesc("lint", "--no-cache", str(hostile(tmp_path, payload, disarm=True)),
                     cwd=tmp_path)
    assert_refused(done)
    assert os.getpriority(os.PRIO_PROCESS, 0) == before


# 7. exit 3 and unbounded memory from hostile input ---------------------------------------


def test_an_unresolvable_proc_path_is_a_refusal_not_a_bug(tmp_path):
    top = _load_yaml_package(tmp_path, "str(xacro.load_yaml('/proc/1/cwd/etc/hostname'))")
    done = robotdesc("expand", "--no-cache", str(top), cwd=tmp_path)
    assert_refused(done)


def _peak_rss_mib(*args: str, cwd: Path) -> tuple[subprocess.CompletedProcess, float]:
    """Run robotdesc in a fresh Python whose children's peak RSS is measured (MiB)."""
    code = ("import resource, subprocess, sys\n"
            "done = subprocess.run(sys.argv[1:], capture_output=True)\n"
            "peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024\n"
            "sys.stdout.write(f'{done.returncode} {peak}\\n')\n"
            "sys.stderr.buffer.write(done.stderr[-4000:])\n")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        filter(None, [SRC, os.environ.get("PYTHONPATH")]))}
    done = subprocess.run([sys.executable, "-c", code, sys.executable, "-m", "robotdesc",
                           *args], capture_output=True, text=True, cwd=cwd, env=env,
                          timeout=300)
    code_text, peak = done.stdout.split()
    return subprocess.CompletedProcess(args, int(code_text), "", done.stderr), float(peak)


@pytest.mark.slow
@pytest.mark.parametrize("stream", [1, 2], ids=["stdout", "stderr"])
def test_a_gigabyte_of_worker_output_keeps_the_parent_small(tmp_path, stream):
    payload = (f"import os\nblock = b'x' * (1 << 20)\n"
               f"for _ in range(1024):\n    os.write({stream}, block)\n")
    path = hostile(tmp_path, payload, disarm=False)
    done, peak = _peak_rss_mib("lint", "--no-cache", str(path), cwd=tmp_path)
    assert peak < 1024, peak
    if stream == 1:
        assert done.returncode == 2 and "output-size limit" in done.stderr, done.stderr
    else:
        assert done.returncode in (0, 1, 2) and "Traceback" not in done.stderr
        assert "were dropped" in done.stderr


def test_a_baseline_written_to_dev_null_is_not_read_back(tmp_path):
    robot = tmp_path / "robot.urdf"
    robot.write_text(ROBOT)
    done = robotdesc("lint", "--no-cache", str(robot), "--write-baseline", os.devnull,
                     cwd=tmp_path)
    assert done.returncode in (0, 1), done.stderr


# 8. the worker never outlives its parent -------------------------------------------------


def _workers_of(parent: int) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            status = (entry / "status").read_text()
            cmdline = (entry / "cmdline").read_bytes()
        except OSError:
            continue
        ppid = next((line.split()[1] for line in status.splitlines()
                     if line.startswith("PPid:")), "")
        if ppid == str(parent) and b"robotdesc.expansion.worker" in cmdline:
            found.append(int(entry.name))
    return found


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    return "\nState:\tZ" not in state


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT, signal.SIGHUP,
                                    signal.SIGKILL], ids=["TERM", "INT", "HUP", "KILL"])
def test_ending_the_parent_ends_the_worker(tmp_path, signum):
    path = hostile(tmp_path, "while True:\n    pass\n", disarm=False)
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        filter(None, [SRC, os.environ.get("PYTHONPATH")]))}
    parent = subprocess.Popen([sys.executable, "-m", "robotdesc", "expand", "--no-cache",
                               "--timeout", "120", str(path)], cwd=tmp_path, env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 30
        workers: list[int] = []
        while not workers and time.monotonic() < deadline:
            time.sleep(0.1)
            workers = _workers_of(parent.pid)
        assert workers, "no worker started"
        time.sleep(0.5)  # the worker is in its loop
        parent.send_signal(signum)
        parent.wait(timeout=30)
        deadline = time.monotonic() + 10
        while any(_alive(w) for w in workers) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not any(_alive(w) for w in workers), "the worker outlived its parent"
        assert b"Traceback" not in parent.stderr.read() if parent.stderr else True
    finally:
        if parent.poll() is None:
            parent.kill()
        for worker in _workers_of(parent.pid):
            os.kill(worker, signal.SIGKILL)


@pytest.mark.parametrize("provenance", ["9:1", "0:1*999999999", "x", "0:1|a@7:2", "0:-1",
                                        "0:1;9:1", "9:1;0:2", "0:1*999999999;0:2"],
                         ids=["past-table", "huge-chain", "garbage", "passed-past-table",
                              "negative", "past-table-in-chain", "own-site-past-table",
                              "huge-own-site-on-a-valid-chain"])
def test_forged_provenance_in_the_document_is_refused(canary, provenance):
    top = str(canary.repo / "attack_pkg" / "urdf" / "attack.urdf.xacro")
    # a valid element first, whose call chain ("0:2") the forged one may share
    xml = (f"<robot name='x' _rd_src='0:1'><link name='k' _rd_src='0:3;0:2'/>"
           f"<link name='l' _rd_src='{provenance}'/></robot>")
    path = hostile(canary.repo, forged({"ok": True, "xml": xml, "files": [top],
                                        "files_read": [top], "packages": [],
                                        "macro_recursion": []}), disarm=True)
    done = canary.run("lint", "--no-cache", str(path))
    assert_refused(done)
    assert "invalid answer" in done.stderr
    canary.assert_silent(done)


def test_an_expansion_entry_sealed_by_another_key_is_a_miss(tmp_path, monkeypatch):
    """A shared or planted cache folder: entries written without this user's key are not
    believed, however well-formed (issue 28, cache poisoning)."""
    top, entry = _stored_entry(tmp_path)
    calls = []
    real = runner.run_worker
    monkeypatch.setattr(runner, "run_worker", lambda *a, **k: calls.append(1) or real(*a, **k))
    options = ExpandOptions(cache_dir=str(tmp_path / "cache"))
    expand_file(top, options=options)
    assert calls == []  # the entry as written is a hit
    monkeypatch.setenv("ROBOTDESC_CACHE_KEY", "a fork's key")
    data = entry.read_bytes()
    expand_file(top, options=options)  # a miss under another key, and rewritten with it
    assert calls == [1] and entry.read_bytes() != data


def test_the_argument_check_reads_nothing_outside_the_package(canary):
    """`name:=value` is checked before the lint by reading the includes statically: an
    include that leads out of the package (`../`, a symlinked folder) is not read."""
    top = _load_yaml_package(canary.repo, "'base'")
    (top.parent / "keys").symlink_to(canary.home / ".ssh")
    top.write_text(top.read_text().replace(
        "<link", '<xacro:include filename="keys/id_test"/>\n'
        '  <xacro:include filename="../../../.ssh/id_test"/>\n  <link'))
    done = canary.run("lint", "--no-cache", str(top), "misspelt:=1")
    assert done.returncode == 2
    canary.assert_silent(done)


def test_the_workers_stderr_cannot_write_escapes_to_the_terminal(canary):
    """xacro's warnings pass from the worker's stderr to the log: control characters, the C1
    CSI among them, are shown as escapes (`robotdesc.printable`), never sent."""
    path = hostile(canary.repo, "import os\nos.write(2, b'warn\\x1b]0;title\\x07 \\xc2\\x9b31m\\n')\n"
                   + forged({"ok": False, "kind": "ExpansionError", "call_stack": [],
                             "span": None, "message": "bad"}), disarm=True)
    done = canary.run("lint", "--no-cache", str(path))
    assert done.returncode == 2
    assert "xacro: warn\\x1b]0;title\\x07 \\x9b31m" in done.stderr
    assert "\x1b" not in done.stderr and "\x9b" not in done.stderr and "\x07" not in done.stderr


def test_a_forged_message_cannot_write_lines_or_escapes_of_its_own(canary):
    path = hostile(canary.repo, forged({
        "ok": False, "kind": "ExpansionError", "call_stack": [], "span": None,
        "message": "bad\n::error file=x::forged\x1b]0;title\x07\x9b31m"}), disarm=True)
    done = canary.run("lint", "--no-cache", str(path))
    assert done.returncode == 2
    assert "\n::error" not in done.stderr and "\x1b" not in done.stderr
    assert "\x9b" not in done.stderr and "\x07" not in done.stderr
