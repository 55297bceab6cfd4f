"""The cache of expensive rules' findings: same findings back, a changed input is a miss."""

from __future__ import annotations

import json
import os

from robotdesc.diagnostics import Finding, ValueChange
from robotdesc.linting import rule_cache
from robotdesc.rules.catalog import get_rule
from robotdesc.source import Provenance, Span

OVERLAP = b"""<robot name="two">
  <link name="a"><collision><geometry><box size="1 1 1"/></geometry></collision></link>
  <link name="b"><collision><origin xyz="-2.8 0 0"/><geometry><box size="1 1 1"/></geometry></collision></link>
  <link name="c"><collision><origin xyz="0 0 10"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="d"><collision><origin xyz="0 0 -10"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="ca" type="fixed"><parent link="c"/><child link="a"/></joint>
  <joint name="cd" type="revolute"><parent link="c"/><child link="d"/><origin xyz="3 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="db" type="revolute"><parent link="d"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""


def test_findings_round_trip(tmp_path):
    finding = Finding("links collide", Provenance(Span("/x/a.xacro", 3, 2), (Span("/x/b.xacro", 9),)),
                      "link:b", "<fix/>")
    rule_cache.store(tmp_path, "k", [finding])
    assert rule_cache.load(tmp_path, "k") == [finding]
    assert rule_cache.load(tmp_path, "missing") is None
    rule_cache.entry_path(tmp_path, "k").write_text("{broken")
    assert rule_cache.load(tmp_path, "k") is None


def test_key_follows_document_options_and_mesh_files(tmp_path):
    rule = get_rule("K201")
    mesh = tmp_path / "m.stl"
    mesh.write_bytes(b"solid x\nendsolid x\n")
    key = rule_cache.rule_key(rule, None, OVERLAP, [str(mesh)])
    assert key == rule_cache.rule_key(rule, None, OVERLAP, [str(mesh)])
    assert key != rule_cache.rule_key(rule, None, OVERLAP + b" ", [str(mesh)])
    assert key != rule_cache.rule_key(rule, "other options", OVERLAP, [str(mesh)])
    os.utime(mesh, ns=(1, 1))
    assert key != rule_cache.rule_key(rule, None, OVERLAP, [str(mesh)])


def test_a_second_lint_gives_the_same_findings_from_the_cache(tmp_path, monkeypatch):
    from robotdesc.expansion import ExpandOptions
    from robotdesc.linting.driver import lint_file

    urdf = tmp_path / "two.urdf"
    urdf.write_bytes(OVERLAP)
    options = ExpandOptions(cache_dir=str(tmp_path / "cache"))
    first = lint_file(str(urdf), expand_options=options, select=["K201"])
    assert [d.code for d in first.diagnostics] == ["K201"]
    assert list((tmp_path / "cache" / "rules").glob("*/*.json"))
    monkeypatch.setattr("robotdesc.rules.registry.run_rule",
                        lambda *a, **k: (_ for _ in ()).throw(AssertionError("rule ran again")))
    second = lint_file(str(urdf), expand_options=options, select=["K201"])
    assert second.diagnostics == first.diagnostics


def test_a_copy_of_a_urdf_gets_findings_that_point_into_the_copy(tmp_path):
    """The same bytes in two places: the cached findings of one never name the other."""
    from robotdesc.expansion import ExpandOptions
    from robotdesc.linting.driver import lint_file

    options = ExpandOptions(cache_dir=str(tmp_path / "cache"))
    paths = []
    for folder in ("a", "b"):
        (tmp_path / folder).mkdir()
        paths.append(tmp_path / folder / "two.urdf")
        paths[-1].write_bytes(OVERLAP)
    for path in paths:
        found = lint_file(str(path), expand_options=options, select=["K201"]).diagnostics
        assert [d.code for d in found] == ["K201"]
        assert all(d.where.span.path == str(path) for d in found), found


def test_a_findings_fix_as_data_survives_the_cache() -> None:
    finding = Finding("m", None, "joint:j", '<axis xyz="0 0 1"/>',
                      (ValueChange("joint:j/axis", "xyz", "0 0 1", 5e-6),))
    assert rule_cache._finding(json.loads(json.dumps(rule_cache._record(finding)))) == finding
