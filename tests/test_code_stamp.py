"""The caches are keyed by robotdesc's code, not only its version number."""

from __future__ import annotations

import os
from pathlib import Path

import robotdesc
from robotdesc import code_stamp


def test_code_id_changes_when_a_module_changes(tmp_path: Path, monkeypatch) -> None:
    package = tmp_path / "robotdesc"
    package.mkdir()
    module = package / "rules.py"
    module.write_text("x = 1\n")
    (package / "code_stamp.py").write_text("")
    monkeypatch.setattr(code_stamp, "__file__", str(package / "code_stamp.py"))
    code_stamp.code_id.cache_clear()
    before = code_stamp.code_id()
    module.write_text("x = 22\n")
    os.utime(module, ns=(1, 1))
    code_stamp.code_id.cache_clear()
    after = code_stamp.code_id()
    code_stamp.code_id.cache_clear()
    assert before != after
    assert before.startswith(f"{robotdesc.__version__}+")
