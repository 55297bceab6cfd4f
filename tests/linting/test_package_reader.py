"""The files beside a description, read for the R1xx rules: read again only when changed."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from robotdesc.linting import package_reader
from robotdesc.linting.package_reader import read_package_files


def _package(tmp_path: Path) -> Path:
    root = tmp_path / "robot_description"
    (root / "launch").mkdir(parents=True)
    (root / "config").mkdir()
    (root / "urdf").mkdir()
    (root / "package.xml").write_text("<package><name>robot_description</name></package>")
    (root / "launch" / "sim.launch.py").write_text("print('a')\n")
    (root / "config" / "controllers.yaml").write_text("a: 1\n")
    (root / "urdf" / "robot.urdf.xacro").write_text("<robot name='r'/>")
    return root


def _texts(root: Path) -> dict[str, str]:
    found = read_package_files(str(root / "urdf" / "robot.urdf.xacro"))
    return {os.path.relpath(f.path, root): f.text for p in found.packages for f in p.files}


def test_a_package_is_read_once_while_nothing_in_it_changes(tmp_path: Path,
                                                             monkeypatch: pytest.MonkeyPatch) -> None:
    root = _package(tmp_path)
    first = _texts(root)
    assert first == {"package.xml": "<package><name>robot_description</name></package>",
                     os.path.join("launch", "sim.launch.py"): "print('a')\n",
                     os.path.join("config", "controllers.yaml"): "a: 1\n"}
    monkeypatch.setattr(package_reader, "_read", lambda *a: pytest.fail("read again"))
    assert _texts(root) == first


def test_a_changed_added_or_removed_file_is_read_again(tmp_path: Path) -> None:
    root = _package(tmp_path)
    _texts(root)
    (root / "config" / "controllers.yaml").write_text("a: 2, b: 3\n")
    assert _texts(root)[os.path.join("config", "controllers.yaml")] == "a: 2, b: 3\n"
    (root / "launch" / "real.launch.py").write_text("pass\n")
    assert os.path.join("launch", "real.launch.py") in _texts(root)
    (root / "launch" / "sim.launch.py").unlink()
    assert os.path.join("launch", "sim.launch.py") not in _texts(root)
    (root / "launch" / "nested").mkdir()
    (root / "launch" / "nested" / "package.xml").write_text("<package/>")
    (root / "launch" / "nested" / "x.launch.py").write_text("pass\n")
    assert os.path.join("launch", "nested", "x.launch.py") not in _texts(root)  # another package
    (root / "launch" / "nested" / "package.xml").unlink()
    assert os.path.join("launch", "nested", "x.launch.py") in _texts(root)


def test_a_file_replaced_by_a_symlink_after_a_read_is_not_followed(tmp_path: Path) -> None:
    """The remembered read is no way around the walk's refusal of symlinks: a YAML file
    swapped for a link to a secret is left out at the next read, not served or followed."""
    root = _package(tmp_path)
    secret = tmp_path / "secret.yaml"
    secret.write_text("token: hunter2\n")
    assert os.path.join("config", "controllers.yaml") in _texts(root)
    target = root / "config" / "controllers.yaml"
    target.unlink()
    target.symlink_to(secret)
    texts = _texts(root)
    assert os.path.join("config", "controllers.yaml") not in texts
    assert not any("hunter2" in text for text in texts.values())
