"""What robotdesc says about its inputs (issue 13): packages found for a file outside any
package, environment variables not passed, xacro arguments, binary files, and a system that
cannot confine the worker."""

from __future__ import annotations

import json
import logging
import os
import subprocess
import sys
from pathlib import Path

import pytest

from robotdesc import errors
from robotdesc.expansion import ExpandOptions, confine, expand_file, looks_binary, runner
from robotdesc.expansion.packages import PackageResolver, PackageResolverConfig

SRC = str(Path(__file__).resolve().parents[2] / "src")
XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
needs_confinement = pytest.mark.skipif(not confine.probe().available,
                                       reason="no Landlock/seccomp: untrusted expansion is refused")


def cli(*args: str, cwd: Path, env: dict | None = None) -> subprocess.CompletedProcess:
    environment = {**os.environ, **(env or {}),
                   "PYTHONPATH": os.pathsep.join(filter(None, [SRC, os.environ.get("PYTHONPATH")]))}
    return subprocess.run([sys.executable, "-m", "robotdesc", *args], capture_output=True,
                          text=True, cwd=cwd, timeout=120, env=environment)


def package(folder: Path, name: str) -> Path:
    folder.mkdir(parents=True)
    (folder / "package.xml").write_text(f"<package format='3'><name>{name}</name></package>")
    return folder


@pytest.fixture
def outside_top(tmp_path: Path) -> tuple[Path, Path]:
    """A top file with no package.xml above it, including a part from a --package-path."""
    pkg = package(tmp_path / "pkgs" / "src" / "arm_parts", "arm_parts")
    (pkg / "urdf").mkdir()
    (pkg / "urdf" / "x.xacro").write_text(
        f'<robot {XACRO_NS}><xacro:macro name="arm"><link name="arm_link"/></xacro:macro>'
        f'<xacro:include filename="$(find arm_parts)/urdf/y.xacro"/></robot>')
    (pkg / "urdf" / "y.xacro").write_text(f'<robot {XACRO_NS}><link name="y_link"/></robot>')
    top = tmp_path / "loose" / "robot.urdf.xacro"
    top.parent.mkdir()
    top.write_text(f'<robot name="r" {XACRO_NS}>\n'
                   f'  <xacro:include filename="$(find arm_parts)/urdf/x.xacro"/>\n'
                   f'  <link name="base"/>\n  <xacro:arm/>\n</robot>\n')
    return top, tmp_path / "pkgs"


@needs_confinement
def test_a_file_outside_any_package_finds_a_package_path_package_in_the_sandbox(outside_top):
    """Issue 13 item 1: the worker's own work (crawling --package-path) is never refused."""
    top, pkgs = outside_top
    safe = expand_file(top, options=ExpandOptions(package_paths=(str(pkgs),), use_cache=False))
    trusted = expand_file(top, options=ExpandOptions(package_paths=(str(pkgs),), use_cache=False,
                                                     trusted=True))
    assert safe.xml == trusted.xml
    assert b'name="arm_link"' in safe.xml and b'name="y_link"' in safe.xml
    assert [p.name for p in safe.packages] == ["arm_parts"]


@needs_confinement
def test_the_same_through_the_cli(outside_top, tmp_path):
    top, pkgs = outside_top
    outputs = [cli("expand", "--no-cache", "--package-path", str(pkgs), str(top), *extra, cwd=tmp_path)
               for extra in ((), ("--trusted",))]
    assert [o.returncode for o in outputs] == [0, 0], outputs[0].stderr
    assert outputs[0].stdout == outputs[1].stdout
    assert "safe mode refuses" not in outputs[0].stderr


def test_candidates_cover_every_source_and_find_needs_no_manifest(tmp_path):
    ws = tmp_path / "ws"
    (ws / ".git").mkdir(parents=True)
    own = package(ws / "src" / "own", "own")
    sibling = package(ws / "src" / "sibling", "sibling")
    extra = package(tmp_path / "extra" / "ex", "ex")
    share = tmp_path / "prefix" / "share" / "amentpkg"
    share.mkdir(parents=True)
    config = PackageResolverConfig(str(own / "robot.urdf.xacro"), (str(tmp_path / "extra"),),
                                   ament_prefix_path=str(tmp_path / "prefix"))
    known = PackageResolver(config).candidates()
    found = {(p.name, p.source) for p in known}
    assert {("ex", "--package-path"), ("own", "enclosing"), ("sibling", "workspace"),
            ("amentpkg", "AMENT_PREFIX_PATH")} <= found
    (sibling / "package.xml").unlink()  # a resolver built from the candidates reads nothing
    offline = PackageResolver(config, known=known)
    assert offline.find("sibling").path == str(sibling)
    assert offline.find("ex").path == str(extra)
    assert offline.find("nope") is None


@needs_confinement
def test_the_sandbox_reads_only_package_folders_never_the_workspace(outside_top):
    top, pkgs = outside_top
    (pkgs / "src" / "loose_secret.xacro").write_text(f'<robot {XACRO_NS}><link name="s"/></robot>')
    roots = runner.worker_roots(top, PackageResolverConfig.from_environment(str(top), (str(pkgs),)))
    assert str(pkgs / "src" / "arm_parts") in roots.data
    assert str(pkgs) not in roots.data and str(pkgs / "src") not in roots.data


# --- the environment (issue 13 item 3) ----------------------------------------------------

ENV_XACRO = f"""<robot name="jackal" {XACRO_NS}>
  <link name="base"/>
  <xacro:if value="$(optenv JACKAL_LASER 0)">
    <link name="laser"/>
  </xacro:if>
</robot>
"""


@needs_confinement
def test_a_set_variable_that_was_not_passed_is_a_warning_and_a_finding(tmp_path):
    source = tmp_path / "jackal.urdf.xacro"
    source.write_text(ENV_XACRO)
    done = cli("lint", "--no-cache", "--format", "json", str(source), cwd=tmp_path,
               env={"JACKAL_LASER": "1"})
    report = json.loads(done.stdout)
    found = [d for d in report["diagnostics"] if d["code"] == "X103"]
    assert len(found) == 1 and found[0]["line"] == 3 and found[0]["severity"] == "warning"
    assert found[0]["message"] == ("JACKAL_LASER is set in your environment but was not passed; "
                                   "the default '0' was used; add --env JACKAL_LASER")
    assert "add --env JACKAL_LASER" in done.stderr
    assert "1" not in found[0]["message"].replace("JACKAL_LASER", "")  # no value is shown


@needs_confinement
def test_a_passed_or_unset_variable_says_nothing(tmp_path):
    source = tmp_path / "jackal.urdf.xacro"
    source.write_text(ENV_XACRO)
    passed = expand_file(source, options=ExpandOptions(use_cache=False, env_allowlist=("JACKAL_LASER",)))
    assert passed.notes == ()
    env = {k: v for k, v in os.environ.items() if k != "JACKAL_LASER"}
    done = cli("lint", "--no-cache", "--format", "json", str(source), cwd=tmp_path, env=env)
    assert not [d for d in json.loads(done.stdout)["diagnostics"] if d["code"] == "X103"]


@needs_confinement
def test_the_worker_gets_names_not_values(tmp_path, monkeypatch):
    monkeypatch.setenv("JACKAL_LASER", "secret-value-42")
    source = tmp_path / "env.urdf.xacro"
    source.write_text(f'<robot name="e" {XACRO_NS}><link name="$(env JACKAL_LASER)"/></robot>')
    with pytest.raises(errors.ExpansionError) as caught:
        expand_file(source, options=ExpandOptions(use_cache=False))
    assert "JACKAL_LASER is set in your environment but was not passed" in caught.value.message
    assert "secret-value-42" not in str(caught.value)


# --- arguments (issue 13 item 4) ----------------------------------------------------------

ARGS_XACRO = f"""<robot name="tracks" {XACRO_NS}>
  <xacro:arg name="main_track_wheels" default="12"/>
  <link name="base_$(arg main_track_wheels)"/>
</robot>
"""


def test_an_undeclared_argument_is_a_usage_error_with_did_you_mean(tmp_path):
    source = tmp_path / "tracks.urdf.xacro"
    source.write_text(ARGS_XACRO)
    done = cli("lint", "--no-cache", "--format", "json", str(source), "main_track_wheel:=18",
               cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    assert done.stdout == ""  # before any lint
    assert "did you mean 'main_track_wheels'?" in done.stderr
    assert "It declares: main_track_wheels." in done.stderr


@needs_confinement
def test_an_undeclared_argument_of_an_unfollowable_include_is_an_error_finding(tmp_path):
    """An include that cannot be followed without expanding may declare it: the expansion
    decides, and says so as X102."""
    source = tmp_path / "tracks.urdf.xacro"
    source.write_text(f'<robot name="t" {XACRO_NS}>\n'
                      '  <xacro:arg name="main_track_wheels" default="12"/>\n'
                      '  <xacro:property name="part" value="none"/>\n'
                      '  <xacro:if value="${part != \'none\'}">'
                      '<xacro:include filename="${part}.xacro"/></xacro:if>\n'
                      '  <link name="base_$(arg main_track_wheels)"/>\n</robot>\n')
    done = cli("lint", "--no-cache", "--format", "json", str(source), "main_track_wheel:=18",
               cwd=tmp_path)
    assert done.returncode == 1, done.stderr
    found = [d for d in json.loads(done.stdout)["diagnostics"] if d["code"] == "X102"]
    assert len(found) == 1 and found[0]["severity"] == "error" and found[0]["line"] == 2
    assert "did you mean 'main_track_wheels'?" in found[0]["message"]


@needs_confinement
def test_an_argument_read_without_declaration_is_no_unknown_argument(tmp_path):
    """TALOS' included files read `$(arg enable_crane)` without an `<xacro:arg>`: xacro
    allows it, and the argument is needed, so it is no X102 (held-out packages)."""
    source = tmp_path / "talos.urdf.xacro"
    source.write_text(f'<robot name="t" {XACRO_NS}>\n  <link name="base_$(arg suffix)"/>\n'
                      '  <link name="${xacro.arg(\'crane\')}"/>\n</robot>\n')
    done = cli("lint", "--no-cache", "--format", "json", str(source), "suffix:=a", "crane:=c",
               cwd=tmp_path)
    assert not [d for d in json.loads(done.stdout)["diagnostics"] if d["code"] == "X102"]
    done = cli("lint", "--no-cache", "--format", "json", str(source), "suffix:=a", "crane:=c",
               "sufix:=b", cwd=tmp_path)
    assert done.returncode == 2
    assert "'sufix' is not declared" in done.stderr and "did you mean 'suffix'?" in done.stderr


@needs_confinement
def test_a_declared_argument_says_nothing(tmp_path):
    source = tmp_path / "tracks.urdf.xacro"
    source.write_text(ARGS_XACRO)
    expanded = expand_file(source, {"main_track_wheels": "18"}, options=ExpandOptions(use_cache=False))
    assert expanded.notes == ()
    assert b'name="base_18"' in expanded.xml


def test_an_argument_without_its_colon_gets_a_hint(tmp_path):
    source = tmp_path / "tracks.urdf.xacro"
    source.write_text(ARGS_XACRO)
    done = cli("lint", str(source), "main_track_wheels=18", cwd=tmp_path)
    assert done.returncode == 2
    assert "main_track_wheels:=18" in done.stderr and "colon" in done.stderr


@needs_confinement
@pytest.mark.parametrize("use", ["$(arg laser)", "${xacro.arg('laser')}"])
def test_an_argument_without_a_default_says_so(tmp_path, use):
    source = tmp_path / "a.urdf.xacro"
    source.write_text(f'<robot name="a" {XACRO_NS}>\n  <link name="l_{use}"/>\n</robot>\n')
    with pytest.raises(errors.ExpansionError) as caught:
        expand_file(source, options=ExpandOptions(use_cache=False))
    assert caught.value.message == "xacro argument 'laser' has no default; pass laser:=VALUE"
    assert caught.value.span.line == 2


# --- binary files (issue 13 item 8) -------------------------------------------------------


def test_a_binary_file_named_as_the_description_is_one_line(tmp_path):
    stl = tmp_path / "part.stl"
    stl.write_bytes(b"\x00" * 80 + (1).to_bytes(4, "little") + bytes(range(256)) * 2)
    done = cli("lint", str(stl), cwd=tmp_path)
    assert done.returncode == 2
    errors_ = [line for line in done.stderr.splitlines() if "error" in line]
    assert errors_ == ["part.stl: error: binary data (.stl), not a URDF or xacro description"]
    assert "\x00" not in done.stdout + done.stderr and "\ufffd" not in done.stdout + done.stderr


def test_binary_data_without_nul_bytes_is_binary_too(tmp_path):
    """An STL header and floats without a NUL byte still hold control bytes XML forbids."""
    stl = tmp_path / "scan.stl"
    stl.write_bytes(b"Exported by CAD" + bytes([0x93, 0x01, 0x7f, 0x1b, 0xc3, 0x05]) * 40)
    done = cli("lint", str(stl), cwd=tmp_path)
    assert done.returncode == 2
    assert done.stderr.splitlines()[0] == \
        "scan.stl: error: binary data (.stl), not a URDF or xacro description"
    assert "\x1b" not in done.stdout + done.stderr


@pytest.mark.parametrize("text", ["<robot name='a'>\t<link name='b'/>\r\n</robot>",
                                  "<?xml version='1.0' encoding='latin-1'?><robot name='\xe9'/>"])
def test_text_with_tabs_or_latin_1_is_not_binary(text):
    assert not looks_binary(text.encode("latin-1"))


# --- no confinement available -------------------------------------------------------------


def test_without_confinement_untrusted_xacro_is_refused_and_said_once(tmp_path, monkeypatch, caplog):
    monkeypatch.setattr(confine, "probe", lambda: confine.Support(False, "no Landlock (test)"))
    monkeypatch.setattr(runner, "_WARNED_UNCONFINED", [])
    source = tmp_path / "r.urdf.xacro"
    source.write_text(f'<robot name="r" {XACRO_NS}><link name="base"/></robot>')
    with caplog.at_level(logging.WARNING, logger="robotdesc"):
        for _ in range(2):
            with pytest.raises(errors.SandboxUnavailable) as caught:
                expand_file(source, options=ExpandOptions(use_cache=False))
            assert caught.value.exit_code == 2
            assert "--trusted" in caught.value.message and "no Landlock (test)" in caught.value.message
    assert sum("cannot confine" in r.getMessage() for r in caplog.records) == 1
    trusted = expand_file(source, options=ExpandOptions(use_cache=False, trusted=True))
    assert b'name="base"' in trusted.xml
    plain = tmp_path / "plain.urdf"
    plain.write_text('<robot name="p"><link name="base"/></robot>')
    assert b'name="base"' in expand_file(plain, options=ExpandOptions(use_cache=False)).xml


@needs_confinement
def test_a_config_default_argument_a_target_does_not_declare_is_not_reported(tmp_path):
    source = tmp_path / "tracks.urdf.xacro"
    source.write_text(ARGS_XACRO)
    (tmp_path / "robotdesc.toml").write_text('[args]\nuse_gazebo = "false"\n')
    done = cli("lint", "--no-cache", "--format", "json", str(source), "main_track_wheels:=3",
               cwd=tmp_path)
    codes = [(d["code"], d["message"]) for d in json.loads(done.stdout)["diagnostics"]]
    assert not any("use_gazebo" in m for _, m in codes)
    done = cli("lint", "--no-cache", str(source), "main_track_wheel:=3", cwd=tmp_path)
    assert done.returncode == 2 and "'main_track_wheel' is not declared" in done.stderr
    assert "use_gazebo" not in done.stderr  # the command line's one only
