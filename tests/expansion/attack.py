"""What the attack tests share: a hostile package run through the command line.

A hostile `.urdf.xacro` uses only `${...}` expressions: it climbs from `xacro.tokenize` to
the builtins (as tests/expansion/fixtures/bad_pkg/urdf/escape_os does) and `exec`s a Python
payload. With `disarm=True` the payload first switches off the in-process audit guard (found
through the closure of xacro's patched `parse`), so that the operating system alone holds.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

SRC = str(Path(__file__).resolve().parents[2] / "src")

#: Python run first when the guard is to be disarmed: it finds the guard through the
#: closures of xacro's patched `parse` (check_file holds it) and sets it unarmed.
DISARM = """
import sys
def _find(f, depth=0):
    for cell in (getattr(f, '__closure__', None) or ()):
        try:
            v = cell.cell_contents
        except ValueError:
            continue
        if type(v).__name__ == 'Guard':
            return v
        if callable(v) and depth < 3:
            found = _find(v, depth + 1)
            if found is not None:
                return found
    return None
_guard = _find(sys.modules['xacro'].parse)
assert _guard is not None, 'guard not found'
_guard.armed = False
"""


def package(folder: Path, name: str) -> Path:
    """A ROS package `folder/name` with a `urdf/` folder and a package.xml."""
    root = folder / name
    (root / "urdf").mkdir(parents=True)
    (root / "package.xml").write_text(
        f'<?xml version="1.0"?><package format="3"><name>{name}</name>'
        '<version>0.0.0</version><description>x</description>'
        '<maintainer email="a@b.c">a</maintainer><license>MIT</license></package>\n')
    return root


def hostile(folder: Path, payload: str, *, disarm: bool) -> Path:
    """A package holding `urdf/attack.urdf.xacro` that runs `payload` with ${...} only."""
    package_dir = package(folder, "attack_pkg")
    code = (DISARM if disarm else "") + payload
    path = package_dir / "urdf" / "attack.urdf.xacro"
    path.write_text(f"""<?xml version="1.0"?>
<robot name="attack" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="d" value="${{'_'*2}}"/>
  <xacro:property name="getset" value="${{python.vars(python.type(lambda: 0))[d + 'globals' + d]}}"/>
  <xacro:property name="getter" value="${{python.vars(python.type(getset))[d + 'get' + d]}}"/>
  <xacro:property name="g" value="${{getter(getset, xacro.tokenize)}}"/>
  <xacro:property name="B" value="${{g[d + 'builtins' + d]}}"/>
  <link name="base"/>
  <link name="x${{B['exec'](B['bytes'].fromhex('{code.encode().hex()}').decode(), dict([(d + 'builtins' + d, B)])) or ''}}"/>
</robot>
""")
    return path


def robotdesc(*args: str, cwd: Path, env: dict | None = None, pass_fds=()) -> subprocess.CompletedProcess:
    environment = {**os.environ, **(env or {}),
                   "PYTHONPATH": os.pathsep.join(filter(None, [SRC, os.environ.get("PYTHONPATH")]))}
    return subprocess.run([sys.executable, "-m", "robotdesc", *args], capture_output=True,
                          text=True, cwd=cwd, timeout=120, env=environment, pass_fds=pass_fds)


def lint(path: Path, cwd: Path, **kwargs) -> subprocess.CompletedProcess:
    return robotdesc("lint", "--no-cache", str(path), cwd=cwd, **kwargs)


def assert_refused(done: subprocess.CompletedProcess, by_sandbox: bool = True) -> None:
    """Exit 2, no traceback, and (by default) a refusal by the guard or the OS sandbox, so
    that an attack failing for an unrelated reason does not pass for a refusal."""
    output = done.stdout + done.stderr
    assert done.returncode == 2, output
    assert "Traceback" not in output
    assert "internal error" not in output
    if by_sandbox:
        assert "safe mode refuses" in output or "sandbox" in output, output


def snapshot(folder: Path) -> dict[str, tuple[bytes, int, int]]:
    return {str(p): (p.read_bytes(), p.stat().st_mtime_ns, p.stat().st_mode)
            for p in sorted(folder.rglob("*")) if p.is_file()}



DISARMED = pytest.mark.parametrize("disarm", [False, True], ids=["guard-armed", "guard-disarmed"])
