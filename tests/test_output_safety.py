"""The one output writer, as a user meets it: no input of a run is ever overwritten, symlinks
and devices are written through and stay what they are, the umask decides the mode, and no
temporary file outlives a run (SIGTERM, SIGINT, or SIGKILL then a new run)."""

from __future__ import annotations

import json
import os
import signal
import stat
import subprocess
import sys
import textwrap
import threading
from pathlib import Path

import pytest

from robotdesc.cli import main
from robotdesc.errors import OutputError
from robotdesc.output import RunInputs, write_output

URDF = """<?xml version="1.0"?>
<robot name="r">
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01"
    ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>
</robot>
"""

TOP = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find demo)/urdf/parts.xacro"/>
  <xacro:part name="base"/>
</robot>
"""

PARTS = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part" params="name">
    <link name="${name}"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01"
      izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
      <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>
  </xacro:macro>
</robot>
"""


@pytest.fixture
def package(tmp_path: Path) -> Path:
    """A package `demo` with a top xacro including a macro file, and a robotdesc.toml."""
    root = tmp_path / "demo"
    (root / "urdf").mkdir(parents=True)
    (root / "package.xml").write_text("<package format='3'><name>demo</name></package>\n")
    (root / "robotdesc.toml").write_text("")
    (root / "urdf" / "robot.urdf.xacro").write_text(TOP)
    (root / "urdf" / "parts.xacro").write_text(PARTS)
    return root


def _snapshot(root: Path) -> dict[str, bytes]:
    return {str(p): p.read_bytes() for p in root.rglob("*") if p.is_file()}


def _refused(capsys, path: Path) -> None:
    err = capsys.readouterr().err
    assert f"refusing to write {path}" in err and "an input of this run" in err, err


# --- inputs are never written ---------------------------------------------------------------


def test_lint_output_onto_the_input_is_refused(tmp_path, capsys):
    urdf = tmp_path / "r.urdf"
    urdf.write_text(URDF)
    assert main(["lint", str(urdf), "-o", str(urdf)]) == 2
    assert urdf.read_text() == URDF
    _refused(capsys, urdf)


def test_write_baseline_onto_the_input_is_refused(tmp_path, capsys):
    urdf = tmp_path / "r.urdf"
    urdf.write_text(URDF)
    assert main(["lint", str(urdf), "--write-baseline", str(urdf)]) == 2
    assert urdf.read_text() == URDF
    _refused(capsys, urdf)


@pytest.mark.parametrize("victim", ["urdf/parts.xacro", "package.xml", "robotdesc.toml",
                                    "urdf/robot.urdf.xacro"])
def test_expand_output_onto_a_file_it_read_is_refused(package, capsys, victim):
    before = _snapshot(package)
    top = package / "urdf" / "robot.urdf.xacro"
    assert main(["expand", str(top), "-o", str(package / victim)]) == 2
    assert _snapshot(package) == before
    _refused(capsys, package / victim)


def test_a_symlink_or_hard_link_to_an_input_is_refused(package, capsys):
    top = package / "urdf" / "robot.urdf.xacro"
    (package / "link.urdf").symlink_to(package / "urdf" / "parts.xacro")
    os.link(package / "urdf" / "parts.xacro", package / "hard.urdf")
    before = _snapshot(package)
    assert main(["expand", str(top), "-o", str(package / "link.urdf")]) == 2
    assert main(["lint", str(top), "-o", str(package / "hard.urdf")]) == 2
    assert _snapshot(package) == before
    assert (package / "link.urdf").is_symlink()


def test_lint_report_onto_an_included_file_is_refused(package, capsys):
    before = _snapshot(package)
    top = package / "urdf" / "robot.urdf.xacro"
    assert main(["lint", str(top), "--format", "json", "-o",
                 str(package / "urdf" / "parts.xacro")]) == 2
    assert _snapshot(package) == before


def test_view_output_onto_an_included_file_is_refused(package, capsys):
    before = _snapshot(package)
    top = package / "urdf" / "robot.urdf.xacro"
    assert main(["view", str(top), "--no-lint", "-o", str(package / "urdf" / "parts.xacro")]) \
        == 2
    assert _snapshot(package) == before
    _refused(capsys, package / "urdf" / "parts.xacro")


def test_srdf_output_onto_an_included_file_is_refused(package, capsys):
    pytest.importorskip("pinocchio")
    before = _snapshot(package)
    top = package / "urdf" / "robot.urdf.xacro"
    assert main(["srdf", str(top), "--samples", "10", "--jobs", "1",
                 "-o", str(package / "urdf" / "parts.xacro")]) == 2
    assert _snapshot(package) == before
    _refused(capsys, package / "urdf" / "parts.xacro")


def test_inertia_write_is_a_patch_never_a_source(package, capsys):
    top = package / "urdf" / "robot.urdf.xacro"
    before = _snapshot(package)
    for victim in ("urdf/parts.xacro", "urdf/robot.urdf.xacro"):
        assert main(["inertia", str(top), "--write", str(package / victim), "--all"]) == 2
        assert _snapshot(package) == before
    patch = package.parent / "inertia.patch"
    assert main(["inertia", str(top), "--write", str(patch), "--all"]) == 0
    assert _snapshot(package) == before and patch.exists()


# --- symlinks, devices, FIFOs ----------------------------------------------------------------


def test_output_to_dev_null_keeps_it_a_device(tmp_path, capsys):
    urdf = tmp_path / "r.urdf"
    urdf.write_text(URDF)
    link = tmp_path / "null"
    link.symlink_to(os.devnull)
    assert main(["lint", str(urdf), "--format", "json", "--fail-on", "error",
                 "-o", str(link)]) == 0
    assert link.is_symlink() and stat.S_ISCHR(os.stat(os.devnull).st_mode)
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".robotdesc-")]


def test_output_to_a_fifo_is_streamed_and_the_fifo_stays(tmp_path):
    urdf = tmp_path / "r.urdf"
    urdf.write_text(URDF)
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    received: list[bytes] = []
    reader = threading.Thread(target=lambda: received.append(fifo.read_bytes()), daemon=True)
    reader.start()
    assert main(["expand", str(urdf), "-o", str(fifo)]) == 0
    reader.join(timeout=30)
    assert b"<robot" in b"".join(received)
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)


def test_output_through_a_symlink_writes_its_target(tmp_path):
    urdf = tmp_path / "r.urdf"
    urdf.write_text(URDF)
    target = tmp_path / "reports" / "real.json"
    target.parent.mkdir()
    target.write_text("old")
    link = tmp_path / "report.json"
    link.symlink_to(target)
    assert main(["lint", str(urdf), "--format", "json", "--fail-on", "error",
                 "-o", str(link)]) == 0
    assert link.is_symlink()
    assert json.loads(target.read_text())  # the report, in the file the link names


# --- modes and temporaries -----------------------------------------------------------------


def _in_child(code: str, **kwargs) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-c", textwrap.dedent(code)], **kwargs)


@pytest.mark.parametrize("umask, expected", [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)])
def test_a_new_output_honours_the_umask(tmp_path, umask, expected):
    target = tmp_path / "out.txt"
    child = _in_child(f"""
        import os
        os.umask({umask})
        from robotdesc.output import write_output
        write_output({str(target)!r}, b"x")
    """)
    assert child.wait(timeout=60) == 0
    assert stat.S_IMODE(target.stat().st_mode) == expected


def test_a_replaced_output_keeps_its_mode(tmp_path):
    target = tmp_path / "out.txt"
    target.write_text("old")
    target.chmod(0o640)
    write_output(str(target), b"new")
    assert target.read_text() == "new" and stat.S_IMODE(target.stat().st_mode) == 0o640


SLOW_WRITER = """
    import sys, time
    from robotdesc.output import write_output

    def chunks():
        yield b"partial" * 1000
        sys.stdout.write("writing\\n"); sys.stdout.flush()
        time.sleep(60)
        yield b"never"

    write_output(sys.argv[1], chunks())
"""


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_during_a_write_leaves_no_temporary(tmp_path, signum):
    target = tmp_path / "out.txt"
    target.write_text("old")
    child = subprocess.Popen([sys.executable, "-c", textwrap.dedent(SLOW_WRITER), str(target)],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert child.stdout.readline() == "writing\n"
    assert [p for p in tmp_path.iterdir() if p.name.startswith(".robotdesc-")]
    child.send_signal(signum)
    code = child.wait(timeout=30)
    assert code != 0  # the signal took its course (killed, or KeyboardInterrupt)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.txt"]
    assert target.read_text() == "old"


def test_a_temporary_left_by_sigkill_is_removed_by_the_next_run(tmp_path, capsys):
    target = tmp_path / "out.json"
    child = subprocess.Popen([sys.executable, "-c", textwrap.dedent(SLOW_WRITER), str(target)],
                             stdout=subprocess.PIPE, text=True)
    assert child.stdout.readline() == "writing\n"
    child.kill()
    child.wait(timeout=30)
    stale = [p for p in tmp_path.iterdir() if p.name.startswith(".robotdesc-")]
    assert len(stale) == 1 and str(child.pid) in stale[0].name
    alive = tmp_path / f".robotdesc-out.json.{os.getppid()}.0.tmp"  # a running process's
    alive.write_text("busy")
    urdf = tmp_path / "r.urdf"
    urdf.write_text(URDF)
    assert main(["lint", str(urdf), "--format", "json", "--fail-on", "error",
                 "-o", str(target)]) == 0
    assert not stale[0].exists() and alive.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        ["out.json", "r.urdf", alive.name])


# --- folders that cannot be written ---------------------------------------------------------


def test_an_output_folder_that_is_a_file_is_exit_2(tmp_path, capsys):
    urdf = tmp_path / "r.urdf"
    urdf.write_text(URDF)
    (tmp_path / "file").write_text("x")
    assert main(["lint", str(urdf), "-o", str(tmp_path / "file" / "out.json")]) == 2
    assert "is a file, not a folder" in capsys.readouterr().err
    assert main(["expand", str(urdf), "-o", str(tmp_path)]) == 2
    assert "it is a folder" in capsys.readouterr().err


def test_the_writer_refuses_inputs_by_name():
    inputs = RunInputs().adding([__file__], "the test itself")
    with pytest.raises(OutputError, match="the test itself"):
        write_output(__file__, b"", inputs)
    assert Path(__file__).read_text().startswith('"""The one output writer')
