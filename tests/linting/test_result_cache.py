"""The whole-result cache: a warm lint prints what the cold one did without linting; a
changed input is a miss; a planted or damaged entry is a miss, never a crash, and can never
make robotdesc show text from a file that is not an input of the lint."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from support import write_limit_robot

from robotdesc.cache_dir import read_entry, write_entry
from robotdesc.cli import main
from robotdesc.expansion import ExpandOptions
from robotdesc.linting import parallel, result_cache
from robotdesc.linting.result import LintResult
from robotdesc.linting.targets import LintTarget

PAST_NS = 1_600_000_000 * 10**9  # 2020: files written "long before" the lint


def _robot(folder: Path, lower: str = "1") -> Path:
    """`support.write_limit_robot`, its files dated long before the lint."""
    top = write_limit_robot(folder, lower)
    for path in folder.iterdir():
        os.utime(path, ns=(PAST_NS, PAST_NS))
    return top


@pytest.fixture()
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    folder = tmp_path / "cache"
    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", str(folder))
    return folder


def _entries(cache: Path) -> list[Path]:
    return sorted((cache / "results").rglob("*.json")) if (cache / "results").exists() else []


def _lint(capsys: pytest.CaptureFixture[str], *words: str) -> tuple[int, str]:
    code = main(["lint", "-q", *words])
    return code, capsys.readouterr().out


def _no_lint(monkeypatch: pytest.MonkeyPatch) -> None:
    def refuse(*args: object, **kwargs: object) -> None:
        raise AssertionError("linted although nothing changed")

    monkeypatch.setattr(parallel, "lint_file", refuse)


def test_a_warm_lint_prints_the_same_report_without_linting(
        tmp_path: Path, cache: Path, capsys: pytest.CaptureFixture[str],
        monkeypatch: pytest.MonkeyPatch) -> None:
    top = _robot(tmp_path)
    cold = _lint(capsys, str(top))
    assert cold[0] == 1 and "J103" in cold[1] and "part.xacro:10" in cold[1]
    assert len(_entries(cache)) == 1
    _no_lint(monkeypatch)
    assert _lint(capsys, str(top)) == cold
    json_cold = main(["lint", "-q", "--format", "json", str(top)])
    assert json_cold == 1 and '"J103"' in capsys.readouterr().out


def test_a_changed_include_is_a_miss(tmp_path: Path, cache: Path,
                                     capsys: pytest.CaptureFixture[str]) -> None:
    top = _robot(tmp_path)
    assert _lint(capsys, str(top))[0] == 1
    _robot(tmp_path, lower="-1")  # the included file changes: the limit is fixed
    code, out = _lint(capsys, str(top))
    assert code == 0 and "J103" not in out


def test_no_cache_and_off_store_nothing(tmp_path: Path, cache: Path,
                                        capsys: pytest.CaptureFixture[str],
                                        monkeypatch: pytest.MonkeyPatch) -> None:
    top = _robot(tmp_path)
    _lint(capsys, str(top), "--no-cache")
    assert _entries(cache) == []
    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", "off")
    _lint(capsys, str(top))
    assert not cache.exists() or _entries(cache) == []
    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", str(cache))
    _lint(capsys, str(top), "--trusted")
    assert _entries(cache) == []


def test_a_file_changed_during_the_lint_is_not_stored(
        tmp_path: Path, cache: Path, capsys: pytest.CaptureFixture[str],
        monkeypatch: pytest.MonkeyPatch) -> None:
    top = _robot(tmp_path)
    lint_file = parallel.lint_file

    def edited_meanwhile(*args: object, **kwargs: object) -> LintResult:
        result = lint_file(*args, **kwargs)  # type: ignore[arg-type]
        (tmp_path / "part.xacro").touch()  # saved by an editor while the rules ran
        return result

    monkeypatch.setattr(parallel, "lint_file", edited_meanwhile)
    _lint(capsys, str(top))
    assert _entries(cache) == []


# ------------------------------------------------------------------ planted and damaged entries


def _planted(tmp_path: Path, cache: Path, capsys: pytest.CaptureFixture[str]
             ) -> tuple[Path, Path, dict]:
    """A robot linted once (its entry written), the entry's path and record."""
    top = _robot(tmp_path)
    _lint(capsys, str(top))
    [entry] = _entries(cache)
    data = read_entry(entry, 1 << 24)
    assert data is not None
    return top, entry, json.loads(data)


def _load(top: Path) -> LintResult | None:
    target = LintTarget(str(top))
    return parallel.cached_result(target, {}, ExpandOptions(), None, ())


def _rewrite(entry: Path, record: object) -> None:
    """Rewrite the entry sealed with this user's key: what its checks must hold against
    beyond the seal (an entry without a valid seal is a miss before any of them)."""
    write_entry(entry, json.dumps(record).encode())


def test_the_entry_as_written_is_a_hit(tmp_path: Path, cache: Path,
                                       capsys: pytest.CaptureFixture[str]) -> None:
    top, _entry, record = _planted(tmp_path, cache, capsys)
    hit = _load(top)
    assert hit is not None and [d.code for d in hit.diagnostics] == ["J103"]
    assert {item[0] for item in record["inputs"]} == {
        str(top.resolve()), str((tmp_path / "part.xacro").resolve())}


@pytest.mark.parametrize("damage", [
    "no inputs", "inputs without the target", "a wrong digest", "a span outside the inputs",
    "a control character", "a relative path", "a bad severity", "a huge count", "a string count",
    "not an object", "truncated", "another key", "a bad rule code", "inputs of the wrong shape",
    "a macro stack outside the inputs", "env of the wrong type"])
def test_a_planted_or_damaged_entry_is_a_miss(tmp_path: Path, cache: Path,
                                              capsys: pytest.CaptureFixture[str],
                                              damage: str) -> None:
    top, entry, record = _planted(tmp_path, cache, capsys)
    finding = record["result"]["diagnostics"][0]
    secret = tmp_path / "secret.txt"
    secret.write_text("password\n" * 20)
    if damage == "no inputs":
        record["inputs"] = []
    elif damage == "inputs without the target":
        record["inputs"] = [i for i in record["inputs"] if not i[0].endswith("robot.urdf.xacro")]
    elif damage == "a wrong digest":
        record["inputs"][0][1] = "0" * 64
    elif damage == "a span outside the inputs":
        finding["where"][0] = [str(secret), 3, 1]
    elif damage == "a control character":
        finding["message"] = "fine\x1b]0;owned\x07"
    elif damage == "a relative path":
        record["inputs"][0][0] = "robot.urdf.xacro"
    elif damage == "a bad severity":
        finding["severity"] = "fatal"
    elif damage == "a huge count":
        record["result"]["suppressed"] = 10**30
    elif damage == "a string count":
        finding["where"][0][1] = "10"
    elif damage == "not an object":
        record = [record]
    elif damage == "truncated":
        write_entry(entry, json.dumps(record)[:100].encode())
        assert _load(top) is None
        return
    elif damage == "another key":
        record["key"] = "f" * 64
    elif damage == "a bad rule code":
        finding["code"] = "J103; rm -rf"
    elif damage == "inputs of the wrong shape":
        record["inputs"] = {"a": "b"}
    elif damage == "a macro stack outside the inputs":
        finding["where"][1] = [[str(secret), 1, 0]]
    elif damage == "env of the wrong type":
        record["env"] = {"HOME": "yes"}
    _rewrite(entry, record)
    assert _load(top) is None
    code, out = _lint(capsys, str(top))  # linted again, the entry rewritten
    assert code == 1 and "J103" in out and "password" not in out and "\x1b" not in out
    assert _load(top) is not None


def test_an_input_replaced_by_a_symlink_is_a_miss(tmp_path: Path, cache: Path,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    top, _entry, _record = _planted(tmp_path, cache, capsys)
    part = tmp_path / "part.xacro"
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "part.xacro").write_bytes(part.read_bytes())  # the same content
    part.unlink()
    part.symlink_to(elsewhere / "part.xacro")
    assert _load(top) is None


def test_an_entry_that_is_a_symlink_or_a_fifo_is_a_miss(
        tmp_path: Path, cache: Path, capsys: pytest.CaptureFixture[str]) -> None:
    top, entry, record = _planted(tmp_path, cache, capsys)
    real = tmp_path / "real.json"
    write_entry(real, json.dumps(record).encode())
    entry.unlink()
    entry.symlink_to(real)
    assert _load(top) is None
    entry.unlink()
    os.mkfifo(entry)
    assert _load(top) is None  # and does not block


def test_an_environment_variable_the_findings_depend_on(
        tmp_path: Path, cache: Path, capsys: pytest.CaptureFixture[str],
        monkeypatch: pytest.MonkeyPatch) -> None:
    top, entry, record = _planted(tmp_path, cache, capsys)
    record["env"] = {"ROBOTDESC_TEST_VARIABLE": False}
    _rewrite(entry, record)
    assert _load(top) is not None
    monkeypatch.setenv("ROBOTDESC_TEST_VARIABLE", "1")
    assert _load(top) is None


def test_a_result_with_an_unresolved_mesh_is_not_stored(
        tmp_path: Path, cache: Path, capsys: pytest.CaptureFixture[str]) -> None:
    top = tmp_path / "r.urdf"
    top.write_text('<robot name="r"><link name="a"><visual><geometry>'
                   '<mesh filename="missing.stl"/></geometry></visual></link></robot>')
    os.utime(top, ns=(PAST_NS, PAST_NS))
    _lint(capsys, str(top))
    assert _entries(cache) == []


def test_the_key_follows_settings() -> None:
    options = ExpandOptions(cache_dir="/tmp/c")
    key = result_cache.result_key("/r.urdf", config=None, args={}, variant=(), select=None,
                                  ignore=(), expand_options=options)
    assert key is not None
    for changed in ({"args": {"a": "1"}}, {"select": ["J"]}, {"ignore": ["J1"]},
                    {"config": "other"}, {"variant": (("a", "1"),)}):
        settings = {"config": None, "args": {}, "variant": (), "select": None, "ignore": (),
                    "expand_options": options, **changed}
        assert result_cache.result_key("/r.urdf", **settings) != key
    assert result_cache.result_key("/r.urdf", config=None, args={}, variant=(), select=None,
                                   ignore=(), expand_options=ExpandOptions(
                                       cache_dir="/tmp/c", use_cache=False)) is None


def test_an_entry_without_this_users_seal_is_a_miss(tmp_path: Path, cache: Path,
                                                    capsys: pytest.CaptureFixture[str],
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    """A shared cache folder: an entry written under another key (another machine, a fork's
    CI job, anyone who can write the folder but lacks the secret) never answers."""
    top, entry, record = _planted(tmp_path, cache, capsys)
    assert _load(top) is not None
    entry.write_text(json.dumps(record))  # the same record, unsealed
    assert _load(top) is None
    monkeypatch.setenv("ROBOTDESC_CACHE_KEY", "another machine's secret")
    _rewrite(entry, record)  # sealed with another key
    monkeypatch.delenv("ROBOTDESC_CACHE_KEY")
    assert _load(top) is None
