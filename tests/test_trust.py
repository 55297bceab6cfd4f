"""`RealPaths` finds what `os.path.realpath` finds, each folder once (robotdesc/trust.py)."""

from __future__ import annotations

import os
from pathlib import Path

from robotdesc.trust import RealPaths, real_within


def test_real_paths_are_realpaths(tmp_path: Path) -> None:
    (tmp_path / "pkg" / "urdf").mkdir(parents=True)
    (tmp_path / "pkg" / "urdf" / "a.xacro").write_text("")
    (tmp_path / "secret").write_text("")
    (tmp_path / "link_folder").symlink_to(tmp_path / "pkg")
    (tmp_path / "pkg" / "urdf" / "out.xacro").symlink_to(tmp_path / "secret")
    (tmp_path / "pkg" / "urdf" / "dangling").symlink_to(tmp_path / "nowhere")
    (tmp_path / "pkg" / "urdf" / "loop").symlink_to(tmp_path / "pkg" / "urdf" / "loop")
    names = ["pkg/urdf/a.xacro", "link_folder/urdf/a.xacro", "link_folder/urdf/out.xacro",
             "pkg/urdf/out.xacro", "pkg/urdf/dangling", "pkg/urdf/missing", "pkg/urdf/..",
             "pkg/urdf/.", "pkg/urdf/", "pkg/urdf/../urdf/a.xacro", "link_folder/../secret",
             "pkg/urdf/loop"]
    real = RealPaths()
    for name in names * 2:  # the second time from the folders it has seen
        path = str(tmp_path / name) if not name.endswith("/") else str(tmp_path) + "/" + name
        assert real(path) == os.path.realpath(path), name
    assert real("relative/a.xacro") == os.path.realpath("relative/a.xacro")
    inside = (os.path.realpath(tmp_path / "pkg"),)
    assert real_within(str(tmp_path / "link_folder/urdf/a.xacro"), inside, RealPaths())
    assert not real_within(str(tmp_path / "pkg/urdf/out.xacro"), inside, RealPaths())
