"""The replay of an unchanged lint (`commands/lint_replay.py`): the third identical run prints
what the second printed without linting or reading the whole-result cache; any change that
could change the answer (an input's bytes, a config put above, the command line, the
environment, a symlink on the way, a foreign entry) runs the lint instead."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from support import write_limit_robot

from robotdesc.cache_dir import read_entry, write_entry
from robotdesc.cli import main
from robotdesc.commands import lint_replay
from robotdesc.linting import parallel, result_cache


def _robot(folder: Path, lower: str = "1") -> Path:
    return write_limit_robot(folder, lower)


@pytest.fixture()
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A cache folder of its own; files written by the test count as settled (no 2 s wait)."""
    folder = tmp_path / "cache"
    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", str(folder))
    monkeypatch.setattr(lint_replay, "SETTLE_NS", 0)
    return folder


def _replays(cache: Path) -> list[Path]:
    return sorted((cache / "replay").rglob("*.json")) if (cache / "replay").exists() else []


def _lint(capsys: pytest.CaptureFixture[str], *words: str) -> tuple[int, str, str]:
    code = main(["lint", *words])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def _no_lint_and_no_cache(monkeypatch: pytest.MonkeyPatch) -> None:
    """Make any lint or whole-result cache read fail the test."""
    def refuse(*args: object, **kwargs: object) -> None:
        raise AssertionError("linted or read the result cache although nothing changed")

    monkeypatch.setattr(parallel, "lint_file", refuse)
    monkeypatch.setattr(result_cache, "load", refuse)


def _stored(tmp_path: Path, capsys: pytest.CaptureFixture[str], cache: Path,
            *words: str) -> tuple[Path, tuple[int, str, str]]:
    """A robot linted twice (cold, then from the result cache: the replay is recorded)."""
    top = _robot(tmp_path / "pkg")
    cold = _lint(capsys, str(top), *words)
    assert _replays(cache) == []
    warm = _lint(capsys, str(top), *words)
    assert warm[:2] == cold[:2]
    assert len(_replays(cache)) == 1
    return top, warm


def test_a_third_identical_lint_is_replayed(tmp_path: Path, cache: Path,
                                            capsys: pytest.CaptureFixture[str],
                                            monkeypatch: pytest.MonkeyPatch) -> None:
    top, warm = _stored(tmp_path, capsys, cache)
    assert warm[0] == 1 and "J103" in warm[1] and "part.xacro:10" in warm[1]
    _no_lint_and_no_cache(monkeypatch)
    assert _lint(capsys, str(top)) == warm
    os.utime(top.parent / "part.xacro")  # touched, same bytes: still the same answer
    assert _lint(capsys, str(top)) == warm


def test_a_changed_include_is_linted(tmp_path: Path, cache: Path,
                                     capsys: pytest.CaptureFixture[str]) -> None:
    top, _ = _stored(tmp_path, capsys, cache)
    _robot(top.parent, lower="-1")  # the limit is fixed in the included file
    code, out, _ = _lint(capsys, str(top))
    assert code == 0 and "J103" not in out


def test_a_config_put_above_is_noticed(tmp_path: Path, cache: Path,
                                       capsys: pytest.CaptureFixture[str]) -> None:
    top, _ = _stored(tmp_path, capsys, cache)
    (tmp_path / "robotdesc.toml").write_text('ignore = ["J103"]\n')
    code, out, _ = _lint(capsys, str(top))
    assert code == 0 and "J103" not in out


def test_another_command_line_or_environment_is_another_run(
        tmp_path: Path, cache: Path, capsys: pytest.CaptureFixture[str],
        monkeypatch: pytest.MonkeyPatch) -> None:
    top, _ = _stored(tmp_path, capsys, cache)
    key = lint_replay.replay_key(["lint", str(top)])
    assert lint_replay.replay_key(["lint", str(top), "--format", "json"]) != key
    monkeypatch.setenv("NO_COLOR", "1")
    assert lint_replay.replay_key(["lint", str(top)]) != key
    code, out, _ = _lint(capsys, str(top), "--format", "json")
    assert code == 1 and json.loads(out)


def test_a_symlinked_folder_put_on_the_way_is_not_replayed(
        tmp_path: Path, cache: Path, capsys: pytest.CaptureFixture[str],
        monkeypatch: pytest.MonkeyPatch) -> None:
    top, _ = _stored(tmp_path, capsys, cache)
    moved = tmp_path / "elsewhere"
    top.parent.rename(moved)
    (tmp_path / "pkg").symlink_to(moved, target_is_directory=True)
    replayed: list[int] = []
    monkeypatch.setattr(lint_replay, "_unchanged", lambda *a: replayed.append(1) or False)
    _lint(capsys, str(top))
    assert replayed == [1]  # asked, and refused: the lint ran
    monkeypatch.undo()
    assert lint_replay.replay(["lint", str(top)]) is None


def test_an_entry_not_sealed_with_the_key_is_not_replayed(
        tmp_path: Path, cache: Path, capsys: pytest.CaptureFixture[str]) -> None:
    top, warm = _stored(tmp_path, capsys, cache)
    (entry,) = _replays(cache)
    raw = read_entry(entry, lint_replay.MAX_ENTRY_BYTES)
    assert raw is not None
    record = json.loads(raw)
    record["out"] = "all clean\n"
    record["code"] = 0
    entry.write_bytes(json.dumps(record).encode())  # planted without the seal
    assert _lint(capsys, str(top))[:2] == warm[:2]
    write_entry(entry, json.dumps({**record, "files": "nothing"}).encode())  # sealed, malformed
    assert _lint(capsys, str(top))[:2] == warm[:2]
    for missing in ("code", "files", "arguments"):
        write_entry(entry, json.dumps({k: v for k, v in record.items() if k != missing}
                                      ).encode())
        assert _lint(capsys, str(top))[:2] == warm[:2]
    write_entry(entry, json.dumps({**record, "files": [[1, 2]]}).encode())
    assert _lint(capsys, str(top))[:2] == warm[:2]


def test_runs_that_write_or_search_are_not_recorded(
        tmp_path: Path, cache: Path, capsys: pytest.CaptureFixture[str]) -> None:
    top = _robot(tmp_path / "pkg")
    report = tmp_path / "report.json"
    for _ in range(2):
        _lint(capsys, str(top), "--format", "json", "--output-file", str(report))
        _lint(capsys, str(top.parent))
    assert _replays(cache) == []


def test_inputs_changed_just_before_the_run_are_not_recorded(
        tmp_path: Path, cache: Path, capsys: pytest.CaptureFixture[str],
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(lint_replay, "SETTLE_NS", 3600 * 10**9)
    top = _robot(tmp_path / "pkg")
    _lint(capsys, str(top))
    _lint(capsys, str(top))
    assert _replays(cache) == []


def test_a_verbose_run_is_not_recorded(tmp_path: Path, cache: Path,
                                       capsys: pytest.CaptureFixture[str]) -> None:
    top = _robot(tmp_path / "pkg")
    for _ in range(2):
        _lint(capsys, "-v", str(top))
    assert _replays(cache) == []


def test_a_closed_pipe_during_a_replay_ends_quietly(
        tmp_path: Path, cache: Path, capsys: pytest.CaptureFixture[str],
        monkeypatch: pytest.MonkeyPatch) -> None:
    top, _ = _stored(tmp_path, capsys, cache)

    def closed(*args: object) -> int:
        raise BrokenPipeError

    silenced: list[bool] = []
    monkeypatch.setattr("robotdesc.cli._silence_stdout", lambda: silenced.append(True))
    monkeypatch.setattr(lint_replay.sys.stdout, "write", closed)
    assert main(["lint", str(top)]) == 0
    assert silenced == [True]


def test_an_input_replaced_by_a_fifo_or_a_symlink_is_not_replayed_nor_opened(
        tmp_path: Path, cache: Path, capsys: pytest.CaptureFixture[str]) -> None:
    top, _ = _stored(tmp_path, capsys, cache)
    part = top.parent / "part.xacro"
    part.rename(tmp_path / "part.saved")
    os.mkfifo(part)  # opening it would block: the replay must only lstat it
    assert lint_replay.replay(["lint", str(top)]) is None
    part.unlink()
    part.symlink_to(tmp_path / "part.saved")  # the same bytes, through a link
    assert lint_replay.replay(["lint", str(top)]) is None
