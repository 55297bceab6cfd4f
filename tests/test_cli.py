"""The command line as a user sees it: `python -m robotdesc ...` in a subprocess.

Exit codes 0 / 1 / 2 (and never 3 on bad input), messages naming file:line, no traceback.
Rule codes are looked up from the registry rather than hard-coded where the test is about the
CLI, not about one rule.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from support import example_robot_urdfs

REPO = Path(__file__).resolve().parents[1]

CLEAN = """<?xml version="1.0"?>
<robot name="clean">
  <link name="base">
    <inertial><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <link name="arm">
    <inertial><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/>
    <child link="arm"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
</robot>
"""
# line 11: the joint whose child link does not exist
BROKEN_LINK = CLEAN.replace('<child link="arm"/>', '<child link="forearm"/>')
MALFORMED = '<?xml version="1.0"?>\n<robot name="r">\n  <link name="a">\n</robot>\n'


def run(*args: str, cwd: Path | None = None,
        env: dict | None = None) -> subprocess.CompletedProcess:
    path = os.pathsep.join(filter(None, [str(REPO / "src"), os.environ.get("PYTHONPATH")]))
    environment = {**os.environ, "PYTHONPATH": path, "NO_COLOR": "1", **(env or {})}
    return subprocess.run([sys.executable, "-m", "robotdesc", *args], capture_output=True,
                          text=True, cwd=cwd, env=environment, timeout=300, check=False)


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


def no_traceback(proc: subprocess.CompletedProcess) -> bool:
    return "Traceback" not in proc.stdout + proc.stderr


@pytest.fixture
def project(tmp_path: Path) -> Path:
    """A folder that is its own VCS root, so no config above it applies."""
    (tmp_path / ".git").mkdir()
    return tmp_path


def lint_json(*args: str, cwd: Path) -> tuple[int, dict]:
    proc = run("lint", "--format", "json", *args, cwd=cwd)
    assert no_traceback(proc), proc.stderr
    return proc.returncode, json.loads(proc.stdout)


def test_help_and_version() -> None:
    proc = run("--help")
    assert proc.returncode == 0 and "lint" in proc.stdout and "expand" in proc.stdout
    proc = run("--version")
    assert proc.returncode == 0 and proc.stdout.startswith("robotdesc ")


def test_clean_robot_exits_0(project: Path) -> None:
    write(project / "clean.urdf", CLEAN)
    proc = run("lint", "clean.urdf", cwd=project)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "All checks passed" in proc.stdout


def test_findings_exit_1_and_point_at_the_line(project: Path) -> None:
    write(project / "broken.urdf", BROKEN_LINK)
    proc = run("lint", "broken.urdf", cwd=project)
    assert proc.returncode == 1
    assert "broken.urdf:11:" in proc.stdout  # the <joint> element's line
    assert '11 |   <joint name="shoulder" type="revolute">' in proc.stdout
    assert "Found " in proc.stdout and no_traceback(proc)
    code, document = lint_json("broken.urdf", cwd=project)
    assert code == 1
    assert any(d["line"] == 11 and d["file"] == str(project / "broken.urdf")
               for d in document["diagnostics"])


def test_ignore_all_and_fail_on(project: Path) -> None:
    write(project / "broken.urdf", BROKEN_LINK)
    assert run("lint", "broken.urdf", "--ignore", "ALL", cwd=project).returncode == 0
    _, document = lint_json("broken.urdf", cwd=project)
    worst = max(("info", "warning", "error").index(d["severity"])
                for d in document["diagnostics"])
    if worst < 2:  # pragma: no cover - the broken reference is expected to be an error
        pytest.fail("a missing child link should be an error")
    assert run("lint", "broken.urdf", "--fail-on", "error", cwd=project).returncode == 1


def test_select_only_the_finding_codes(project: Path) -> None:
    write(project / "broken.urdf", BROKEN_LINK)
    _, document = lint_json("broken.urdf", cwd=project)
    codes = sorted({d["code"] for d in document["diagnostics"]})
    code, selected = lint_json("broken.urdf", "--select", codes[0], cwd=project)
    assert code == 1 and {d["code"] for d in selected["diagnostics"]} == {codes[0]}


def test_inline_suppression_and_unused_suppression(project: Path) -> None:
    write(project / "broken.urdf", BROKEN_LINK)
    _, document = lint_json("broken.urdf", cwd=project)
    codes = ", ".join(sorted({d["code"] for d in document["diagnostics"] if d["line"] == 11}))
    assert codes
    suppressed = BROKEN_LINK.replace("  <joint name=", f"  <!-- robotdesc: ignore {codes} -->\n"
                                                     "  <joint name=", 1)
    write(project / "broken.urdf", suppressed)
    code, after = lint_json("broken.urdf", cwd=project)
    assert not [d for d in after["diagnostics"] if d["line"] == 12]
    assert after["summary"]["suppressed"] >= 1

    unused = CLEAN.replace("  <joint name=", f"  <!-- robotdesc: ignore {codes} -->\n"
                                             "  <joint name=", 1)
    write(project / "clean.urdf", unused)
    code, report = lint_json("clean.urdf", cwd=project)
    assert code == 1
    assert [(d["code"], d["name"], d["line"]) for d in report["diagnostics"]] == [
        ("RD001", "unused-suppression", 11)] * len(codes.split(", "))


def test_config_is_discovered_and_validated(project: Path) -> None:
    write(project / "urdf" / "broken.urdf", BROKEN_LINK)
    write(project / "pyproject.toml", '[tool.robotdesc]\nignore = ["ALL"]\n')
    assert run("lint", "urdf/broken.urdf", cwd=project).returncode == 0
    write(project / "pyproject.toml", '[tool.robotdesc]\nfail-on = "fatal"\n')
    proc = run("lint", "urdf/broken.urdf", cwd=project)
    assert proc.returncode == 2 and no_traceback(proc)
    assert "pyproject.toml:2: error: invalid configuration" in proc.stderr
    write(project / "other.toml", 'ignore = ["ALL"]\n')
    assert run("lint", "urdf/broken.urdf", "--config", "other.toml",
               cwd=project).returncode == 0


def test_malformed_xml_exits_2_naming_file_and_line(project: Path) -> None:
    write(project / "bad.urdf", MALFORMED)
    proc = run("lint", "bad.urdf", cwd=project)
    assert proc.returncode == 2 and no_traceback(proc)
    assert proc.stderr.startswith("bad.urdf:")
    assert ": error: " in proc.stderr
    location = proc.stderr.split(": error:")[0].split(":")
    assert int(location[1]) >= 3
    assert "1 file could not be checked." in proc.stdout


def test_json_lists_input_failures(project: Path) -> None:
    write(project / "bad.urdf", MALFORMED)
    proc = run("lint", "bad.urdf", "--format", "json", cwd=project)
    assert proc.returncode == 2
    document = json.loads(proc.stdout)
    assert document["failures"][0]["kind"] == "XmlSyntaxError"
    assert document["failures"][0]["file"] == str(project / "bad.urdf")


def test_worst_exit_code_wins_across_paths(project: Path) -> None:
    write(project / "clean.urdf", CLEAN)
    write(project / "broken.urdf", BROKEN_LINK)
    write(project / "bad.urdf", MALFORMED)
    assert run("lint", "clean.urdf", "broken.urdf", cwd=project).returncode == 1
    proc = run("lint", "clean.urdf", "missing.urdf", "broken.urdf", cwd=project)
    assert proc.returncode == 2
    assert "missing.urdf: error: no such file or directory" in proc.stderr
    assert "broken.urdf:11:" in proc.stdout  # the other files are still linted


def test_directory_lints_its_descriptions(project: Path) -> None:
    write(project / "pkg" / "urdf" / "clean.urdf", CLEAN)
    write(project / "pkg" / "urdf" / "macros.xacro", "<robot/>")  # a macro library: skipped
    code, document = lint_json("pkg", cwd=project)
    assert code == 0 and document["summary"]["files_checked"] == 1


def test_output_file_is_written(project: Path) -> None:
    write(project / "broken.urdf", BROKEN_LINK)
    proc = run("lint", "broken.urdf", "--format", "json", "--output-file", "report.json",
               cwd=project)
    assert proc.returncode == 1 and proc.stdout == ""
    assert json.loads((project / "report.json").read_text())["summary"]["files_checked"] == 1


@pytest.mark.parametrize("args", [
    ("lint",), ("lint", "x.urdf", "--format", "yaml"), ("frobnicate",),
    ("lint", "x.urdf", "--select", "NOSUCHRULE"), ("rule", "NOSUCHRULE"),
])
def test_usage_errors_exit_2(project: Path, args: tuple[str, ...]) -> None:
    write(project / "x.urdf", CLEAN)
    proc = run(*args, cwd=project)
    assert proc.returncode == 2 and no_traceback(proc)
    assert proc.stderr


def test_rules_and_rule(project: Path) -> None:
    proc = run("rules")
    assert proc.returncode == 0
    assert proc.stdout.splitlines()[0].split()[:4] == ["CODE", "NAME", "FAMILY", "SEVERITY"]
    assert any(line.split()[:2] == ["RD001", "unused-suppression"]
               for line in proc.stdout.splitlines())
    proc = run("rule", "unused-suppression")
    assert proc.returncode == 0
    assert proc.stdout.startswith("RD001 unused-suppression\n")
    assert "Default severity:" in proc.stdout
    assert "Default: on" in proc.stdout


def test_rules_mark_each_rule_default_on_or_off(project: Path) -> None:
    text = run("rules").stdout.splitlines()
    assert text[0].split()[:5] == ["CODE", "NAME", "FAMILY", "SEVERITY", "DEFAULT"]
    assert any(line.split()[:1] == ["K102"] and line.split()[4] == "off" for line in text)
    assert any(line.split()[:1] == ["I204"] and line.split()[4] == "on" for line in text)
    proc = run("rules", "--format", "json")
    assert proc.returncode == 0
    states = {entry["code"]: entry["default"] for entry in json.loads(proc.stdout)}
    assert states["I204"] == "on" and states["I206"] == "off" and states["J110"] == "off"
    assert "Default: off" in run("rule", "K203").stdout


def test_expand_plain_urdf_to_a_file_and_never_over_the_input(project: Path) -> None:
    write(project / "clean.urdf", CLEAN)
    proc = run("expand", "clean.urdf", "-o", "out.urdf", cwd=project)
    assert proc.returncode == 0, proc.stderr
    written = (project / "out.urdf").read_text()
    assert "<robot" in written and "_rd_src" not in written
    proc = run("expand", "clean.urdf", "-o", "./clean.urdf", cwd=project)
    assert proc.returncode == 2 and "refusing to write" in proc.stderr
    assert (project / "clean.urdf").read_text() == CLEAN


def test_expand_xacro_to_stdout_with_arguments(project: Path) -> None:
    write(project / "robot.urdf.xacro", """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="prefix" default="a_"/>
  <link name="$(arg prefix)base"/>
</robot>
""")
    proc = run("expand", "robot.urdf.xacro", "prefix:=left_", cwd=project)
    assert proc.returncode == 0, proc.stderr
    assert 'name="left_base"' in proc.stdout and "_rd_src" not in proc.stdout
    # arguments after options, as xacro and roslaunch users write them
    proc = run("expand", "robot.urdf.xacro", "--no-cache", "prefix:=right_", cwd=project)
    assert proc.returncode == 0, proc.stderr
    assert 'name="right_base"' in proc.stdout
    proc = run("expand", "robot.urdf.xacro", "--no-cache", "--bogus", "prefix:=x", cwd=project)
    assert proc.returncode == 2 and "unrecognized arguments: --bogus" in proc.stderr


def test_expand_undefined_property_reports_its_line(project: Path) -> None:
    write(project / "robot.urdf.xacro", """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base"/>
  <link name="${no_such_property}"/>
</robot>
""")
    proc = run("lint", "robot.urdf.xacro", cwd=project)
    assert proc.returncode == 2 and no_traceback(proc)
    assert proc.stderr.startswith("robot.urdf.xacro:4")


def test_verbose_logs_to_stderr(project: Path) -> None:
    write(project / "clean.urdf", CLEAN)
    proc = run("lint", "clean.urdf", "--verbose", cwd=project)
    assert proc.returncode == 0 and "robotdesc: linting clean.urdf" in proc.stderr


def test_every_example_robot_data_urdf_lints_without_internal_error() -> None:
    urdfs = example_robot_urdfs()
    if not urdfs:
        pytest.skip("example-robot-data is not installed")
    proc = run("lint", "--format", "json", *map(str, urdfs))
    assert proc.returncode in (0, 1, 2), proc.stderr[-2000:]
    assert no_traceback(proc), proc.stderr[-2000:]
    document = json.loads(proc.stdout)
    assert document["summary"]["files_checked"] + document["summary"]["files_not_checked"] \
        == len(urdfs)


def _raise(exc: BaseException):
    def fail(*args, **kwargs):
        raise exc
    return fail


def test_internal_error_exits_3_with_a_bug_report_hint(project: Path, monkeypatch, capsys) -> None:
    from robotdesc import cli
    from robotdesc.linting import parallel

    write(project / "clean.urdf", CLEAN)
    monkeypatch.setattr(parallel, "lint_file", _raise(RuntimeError("kaput")))
    assert cli.main(["lint", str(project / "clean.urdf")]) == 3
    err = capsys.readouterr().err
    assert "internal error: RuntimeError: kaput" in err and "please report it" in err
    assert "Traceback" not in err
    assert cli.main(["lint", str(project / "clean.urdf"), "--verbose"]) == 3
    assert "Traceback" in capsys.readouterr().err


def test_keyboard_interrupt_exits_130(project: Path, monkeypatch, capsys) -> None:
    from robotdesc import cli
    from robotdesc.linting import parallel

    write(project / "clean.urdf", CLEAN)
    monkeypatch.setattr(parallel, "lint_file", _raise(KeyboardInterrupt()))
    assert cli.main(["lint", str(project / "clean.urdf")]) == 130
    assert "interrupted" in capsys.readouterr().err


@pytest.mark.parametrize("argv", [["--help"], ["lint", "--help"], ["expand", "--help"],
                                  ["rule", "--help"]])
def test_help_imports_no_heavy_module(argv: list[str]) -> None:
    code = ("import sys; from robotdesc.cli import main\n"
            f"try:\n    main({argv!r})\nexcept SystemExit:\n    pass\n"
            "heavy = {'lxml', 'xacro', 'rich', 'numpy', 'trimesh', 'yaml'} & "
            "{m.split('.')[0] for m in sys.modules}\n"
            "print(sorted(heavy))")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(REPO / "src")}, timeout=60,
                          check=False)
    assert proc.stdout.strip().splitlines()[-1] == "[]"


BAD_XACRO = {
    "doctype": """<?xml version="1.0"?>
<!DOCTYPE robot [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;">]>
<robot name="r"><link name="&b;"/></robot>
""",
    "eval-os": """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base"/>
  <link name="${__import__('os').system('echo pwned')}"/>
</robot>
""",
    "self-include": """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base"/>
  <xacro:include filename="robot.urdf.xacro"/>
</robot>
""",
}


@pytest.mark.parametrize("case", sorted(BAD_XACRO))
def test_bad_xacro_exits_2_with_a_located_message(project: Path, case: str) -> None:
    write(project / "robot.urdf.xacro", BAD_XACRO[case])
    proc = run("lint", "robot.urdf.xacro", cwd=project)
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert no_traceback(proc)
    assert "pwned" not in (proc.stdout + proc.stderr).splitlines()  # os.system did not run
    assert proc.stderr.startswith("robot.urdf.xacro:"), proc.stderr


def test_expand_says_when_the_root_is_no_robot(project: Path) -> None:
    """A package.xml named by mistake expands as xacro would (exit 0), with a note."""
    write(project / "package.xml", '<?xml version="1.0"?>\n<!-- x -->\n<package format="3">'
          "<name>x</name></package>\n")
    proc = run("expand", "package.xml", cwd=project)
    assert proc.returncode == 0 and "<package" in proc.stdout
    assert "the root element is <package>, not <robot>" in proc.stderr
    write(project / "clean.urdf", CLEAN)
    assert "root element" not in run("expand", "clean.urdf", cwd=project).stderr
