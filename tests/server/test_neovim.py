"""The Neovim set-up of docs/editors.md, run as written in a headless Neovim (issue 34,
item 4): it starts `robotdesc server`, and a broken file gets its finding as a diagnostic, a
clean one none. Skipped, saying why, when no Neovim is installed (CI installs Debian's 0.7)."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("pygls")

REPO = Path(__file__).resolve().parents[2]
EDITORS = REPO / "docs" / "editors.md"
NVIM = shutil.which("nvim")
pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(NVIM is None, reason="Neovim is not installed (CI installs "
                                                      "Debian's neovim: .ci/run)")]

BROKEN = """<?xml version="1.0"?>
<robot name="r">
  <link name="base">
    <inertial><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <link name="arm">
    <inertial><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 2"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
</robot>
"""
# Waits for the server's publication, then writes "codes: J107,..." (or "timeout") to a file.
PROBE = """
local done = vim.wait(90000, function()
  return #vim.diagnostic.get(0) > 0 or vim.g.robotdesc_published == true
end, 100)
local codes = {}
for _, d in ipairs(vim.diagnostic.get(0)) do table.insert(codes, tostring(d.code)) end
local out = io.open(vim.env.PROBE_OUT, "w")
out:write((done and "codes: " or "timeout: ") .. table.concat(codes, ","))
out:close()
vim.cmd("qall!")
"""
# Marks any publication for the buffer, also an empty one (a clean file).
HOOK = """
local default = vim.lsp.handlers["textDocument/publishDiagnostics"]
vim.lsp.handlers["textDocument/publishDiagnostics"] = function(err, result, ctx, config)
  default(err, result, ctx, config)
  vim.g.robotdesc_published = true
end
"""


def _snippet() -> str:
    text = EDITORS.read_text(encoding="utf-8")
    section = text[text.index("### Neovim"):]
    return re.search(r"```lua\n(.*?)```", section, re.DOTALL).group(1)


def _run(tmp_path: Path, name: str, text: str) -> str:
    package = tmp_path / "pkg"
    package.mkdir(exist_ok=True)
    (package / "package.xml").write_text(
        "<package format='3'><name>pkg</name><version>0.0.0</version>"
        "<description>d</description><maintainer email='a@b.c'>a</maintainer>"
        "<license>MIT</license></package>")
    robot = package / name
    robot.write_text(text)
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir(exist_ok=True)
    launcher = bin_dir / "robotdesc"  # `robotdesc` as the snippet calls it, this checkout's
    launcher.write_text(f"#!/bin/sh\nexec {sys.executable} -m robotdesc \"$@\"\n")
    launcher.chmod(0o755)
    init = tmp_path / "init.lua"
    init.write_text(_snippet() + HOOK)
    probe = tmp_path / "probe.lua"
    probe.write_text(PROBE)
    out = tmp_path / f"{name}.out"
    env = {**os.environ, "PATH": f"{bin_dir}{os.pathsep}{os.environ['PATH']}",
           "PYTHONPATH": str(REPO / "src"), "PROBE_OUT": str(out),
           "ROBOTDESC_CACHE_DIR": str(tmp_path / "cache"), "XDG_STATE_HOME": str(tmp_path),
           "XDG_DATA_HOME": str(tmp_path), "XDG_CONFIG_HOME": str(tmp_path)}
    subprocess.run([NVIM, "--headless", "-n", "-i", "NONE", "-u", str(init), str(robot),
                    "-c", f"luafile {probe}"], env=env, timeout=150, check=False,
                   stdin=subprocess.DEVNULL, capture_output=True)
    return out.read_text() if out.exists() else "no answer"


def test_the_documented_setup_shows_a_finding(tmp_path: Path) -> None:
    assert "J107" in _run(tmp_path, "broken.urdf", BROKEN).removeprefix("codes: ").split(",")


def test_the_documented_setup_shows_a_clean_file_as_clean(tmp_path: Path) -> None:
    clean = BROKEN.replace('xyz="0 0 2"', 'xyz="0 0 1"')
    assert _run(tmp_path, "clean.urdf", clean) == "codes: "
