"""Bad input is refused with its file and line, and nothing escapes the sandbox."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from robotdesc import errors
from robotdesc.expansion import ExpandOptions, expand_file

BAD = Path(__file__).parent / "fixtures" / "bad_pkg" / "urdf"

CASES = [
    # file, error type, line, words in the message
    ("malformed.urdf.xacro", errors.XmlSyntaxError, 4, "mismatched tag"),
    ("truncated.urdf.xacro", errors.XmlSyntaxError, 4, "unclosed token"),
    ("billion_laughs.urdf.xacro", errors.XmlSyntaxError, 2, "DOCTYPE"),
    ("external_entity.urdf.xacro", errors.XmlSyntaxError, 2, "DOCTYPE"),
    ("escape_os.urdf.xacro", errors.SandboxViolation, 9, "os.system"),
    ("eval_os.urdf.xacro", errors.SandboxViolation, 6, "os.system"),
    ("recurse_forever.urdf.xacro", errors.LimitExceeded, 5, "nested deeper"),
    ("include_self.urdf.xacro", errors.ExpansionError, 4, "include cycle"),
    ("huge_string.urdf.xacro", errors.LimitExceeded, 4, "memory limit"),
    ("undefined_property.urdf.xacro", errors.ExpansionError, 6, "'height' is not defined"),
    ("unknown_package.urdf.xacro", errors.ExpansionError, 4, "unknown package 'no_such_package_anywhere'"),
    ("escape_include.urdf.xacro", errors.SandboxViolation, 4, "escapes the package root"),
]


@pytest.mark.parametrize("name, error, line, words", CASES, ids=[c[0] for c in CASES])
def test_bad_input_is_refused_at_its_line(name, error, line, words, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(error) as caught:
        expand_file(BAD / name, options=ExpandOptions(use_cache=False, memory_mb=1024))
    assert caught.value.span is not None
    assert caught.value.span.path == str(BAD / name)
    assert caught.value.span.line == line
    assert words in caught.value.message
    assert caught.value.exit_code == 2
    assert not (tmp_path / "ESCAPE_MARKER").exists()


def test_recursion_error_names_a_bounded_call_chain():
    with pytest.raises(errors.LimitExceeded) as caught:
        expand_file(BAD / "recurse_forever.urdf.xacro", options=ExpandOptions(use_cache=False))
    chain = caught.value.call_stack
    assert 2 <= len(chain) <= 12
    assert chain[-1].line == 7  # the outermost call, in the robot body


def test_trusted_mode_lifts_the_package_root_limit():
    expanded = expand_file(BAD / "escape_include.urdf.xacro",
                           options=ExpandOptions(use_cache=False, trusted=True))
    assert b'name="secret"' in expanded.xml


def test_wall_clock_limit_stops_a_slow_expansion():
    with pytest.raises(errors.LimitExceeded) as caught:
        expand_file(BAD / "recurse_forever.urdf.xacro",
                    options=ExpandOptions(use_cache=False, timeout_s=0.5, max_macro_depth=10**6))
    assert "0.5 s" in caught.value.message or "limit" in caught.value.message


def test_missing_file_is_an_input_error(tmp_path):
    with pytest.raises(errors.InputError) as caught:
        expand_file(tmp_path / "nope.urdf.xacro")
    assert "no such file" in caught.value.message


def test_the_worker_environment_is_clean(tmp_path, monkeypatch):
    monkeypatch.setenv("ROBOTDESC_SECRET_TOKEN", "hunter2")
    source = tmp_path / "env.urdf.xacro"
    source.write_text('<robot name="e" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                      '<link name="$(env ROBOTDESC_SECRET_TOKEN)"/></robot>')
    with pytest.raises(errors.ExpansionError) as caught:
        expand_file(source, options=ExpandOptions(use_cache=False))
    assert "allowlist" in caught.value.message
    assert "set in your environment but was not passed" in caught.value.message
    assert "add --env ROBOTDESC_SECRET_TOKEN" in caught.value.message
    assert "hunter2" not in str(caught.value)
    assert os.environ["ROBOTDESC_SECRET_TOKEN"] == "hunter2"


def test_unknown_macro_through_xacro_call_is_named(tmp_path):
    source = tmp_path / "call.urdf.xacro"
    source.write_text('<robot name="c" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                      '  <link name="base"/>\n'
                      '  <xacro:call macro="missing_macro"/>\n'
                      '</robot>\n')
    with pytest.raises(errors.ExpansionError) as caught:
        expand_file(source, options=ExpandOptions(use_cache=False))
    assert caught.value.span.line == 3
    assert "missing_macro" in caught.value.message and "undefined" in caught.value.message


@pytest.mark.parametrize("name, error, line, words", CASES, ids=[c[0] for c in CASES])
def test_cli_exits_2_naming_file_and_line_without_a_traceback(name, error, line, words, tmp_path):
    import subprocess
    import sys

    src = str(Path(__file__).resolve().parents[2] / "src")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [src, os.environ.get("PYTHONPATH")]))}
    done = subprocess.run([sys.executable, "-m", "robotdesc", "lint", "--no-cache", str(BAD / name)],
                          capture_output=True, text=True, cwd=tmp_path, timeout=120, env=env)
    assert done.returncode == 2, done.stdout + done.stderr
    assert f"{name}:{line}" in done.stderr
    assert "Traceback" not in done.stdout + done.stderr
    assert not (tmp_path / "ESCAPE_MARKER").exists()


@pytest.mark.parametrize("declared", ["ascii", "ISO-8859-1"])
def test_a_utf8_file_is_read_as_utf8_whatever_it_declares(tmp_path, declared, caplog):
    """xacro reads files as UTF-8 text in a UTF-8 locale: so does robotdesc, and it says
    when the declaration disagrees (issue 28)."""
    top = tmp_path / "robot.urdf.xacro"
    top.write_bytes(f'<?xml version="1.0" encoding="{declared}"?>\n<robot name="r" '
                    'xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="bé"/>'
                    '<xacro:element xacro:name="a:b"/></robot>\n'.encode("utf-8"))
    expanded = expand_file(top, options=ExpandOptions(use_cache=False))
    assert 'name="bé"'.encode() in expanded.xml and b"<a:b" in expanded.xml
    assert "the file is UTF-8" in caplog.text
