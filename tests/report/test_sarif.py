"""The SARIF report: snapshot, validity against the official SARIF 2.1.0 schema, locations at
the xacro source with the macro call chain as related locations, and rule metadata."""

from __future__ import annotations

import json
import re
from pathlib import Path

import jsonschema
import pytest

from robotdesc.report.sarif import render_sarif, rule_descriptor, sarif_log
from robotdesc.rules.catalog import all_rules
from robotdesc.rules.docs import render_rules_markdown

from .ci_samples import DATA, RULES, build_ci_sample, check_snapshot, normalise

REPO = Path(__file__).resolve().parents[2]
SCHEMA = json.loads((DATA / "sarif-schema-2.1.0.json").read_text(encoding="utf-8"))


def validate(document: dict) -> None:
    jsonschema.Draft7Validator(SCHEMA, format_checker=jsonschema.FormatChecker()).validate(
        document)


@pytest.fixture
def sample(tmp_path):
    return build_ci_sample(tmp_path)


def test_sarif_snapshot(sample) -> None:
    results, failures, root = sample
    text = render_sarif(results, failures, rules=RULES, cwd=str(root))
    validate(json.loads(text))
    check_snapshot("sample.sarif.json", normalise(text, root))


def test_results_point_at_xacro_lines_with_the_macro_chain(sample) -> None:
    results, failures, root = sample
    run = sarif_log(results, failures, rules=RULES, cwd=str(root))["runs"][0]
    in_macro = run["results"][0]
    location = in_macro["locations"][0]["physicalLocation"]
    assert location == {"artifactLocation": {"uri": "arm.xacro", "uriBaseId": "%SRCROOT%"},
                        "region": {"startLine": 3, "startColumn": 2}}
    related = [(r["id"], r["physicalLocation"]["region"]["startLine"])
               for r in in_macro["relatedLocations"]]
    assert related == [(1, 3), (2, 4)]
    assert "[robot.urdf.xacro:3](1) <- [robot.urdf.xacro:4](2)" in in_macro["message"]["text"]
    assert in_macro["ruleIndex"] == 0 and in_macro["level"] == "error"
    assert in_macro["locations"][0]["logicalLocations"][0]["fullyQualifiedName"] == \
        "joint:left_elbow"
    assert run["results"][2]["level"] == "note"  # info
    assert "region" not in run["results"][2]["locations"][0]["physicalLocation"]
    assert len(run["results"]) == 3  # the variant's finding is the first one's
    assert in_macro["properties"]["variants"] == ["[default arguments]", "[side=left]"]
    assert in_macro["properties"]["inAllVariants"] is True
    only = run["results"][1]
    assert only["properties"]["variants"] == ["[default arguments]"]
    assert "(only in variant [default arguments])" in only["message"]["text"]
    assert only["partialFingerprints"] != in_macro["partialFingerprints"]
    assert run["originalUriBaseIds"]["%SRCROOT%"]["uri"] == root.as_uri() + "/"


def test_failures_are_error_notifications(sample) -> None:
    results, failures, root = sample
    invocation = sarif_log(results, failures, rules=RULES, cwd=str(root))["runs"][0][
        "invocations"][0]
    assert invocation["executionSuccessful"] is False
    note = invocation["toolExecutionNotifications"][0]
    assert note["level"] == "error" and "undefined property" in note["message"]["text"]
    clean = sarif_log(results, [], rules=RULES, cwd=str(root))["runs"][0]["invocations"][0]
    assert clean["executionSuccessful"] is True


def test_paths_outside_the_root_are_absolute_file_uris(sample, tmp_path_factory) -> None:
    results, failures, root = sample
    elsewhere = tmp_path_factory.mktemp("elsewhere")
    document = sarif_log(results, failures, rules=RULES, cwd=str(elsewhere))
    validate(document)
    uri = document["runs"][0]["results"][0]["locations"][0]["physicalLocation"][
        "artifactLocation"]
    assert uri == {"uri": (root / "arm.xacro").as_uri()}


def test_every_registered_rule_has_metadata_and_a_docs_anchor() -> None:
    rules_md = render_rules_markdown()  # docs/rules.md, as a test keeps it
    anchors = {"-".join(re.sub(r"[^\w\- ]", "", m.group(1).lower()).split())
               for m in re.finditer(r"^## (.+)$", rules_md, re.MULTILINE)}
    document = sarif_log([], [], cwd=str(REPO))
    validate(document)
    descriptors = document["runs"][0]["tool"]["driver"]["rules"]
    assert [d["id"] for d in descriptors] == [r.code for r in all_rules()]
    for descriptor in descriptors:
        assert descriptor["name"] and descriptor["shortDescription"]["text"]
        assert descriptor["help"]["text"] and descriptor["fullDescription"]["text"]
        anchor = descriptor["helpUri"].split("#", 1)[1]
        assert anchor in anchors, f"{descriptor['id']}: no heading for #{anchor} in rules.md"


def test_rule_help_markdown_marks_sections() -> None:
    descriptor = rule_descriptor(RULES[0])
    assert descriptor["fullDescription"]["text"] == "Finds a revolute joint without a `<limit>`."
    assert "**Why is this bad?**" in descriptor["help"]["markdown"]
    assert descriptor["defaultConfiguration"] == {"level": "error"}


def test_schema_rejects_a_broken_log(sample) -> None:
    results, failures, root = sample
    document = sarif_log(results, failures, rules=RULES, cwd=str(root))
    document["runs"][0]["results"][0]["level"] = "fatal"
    with pytest.raises(jsonschema.ValidationError):
        validate(document)
