"""The JSON report: every documented field, validated against the published schema."""

from __future__ import annotations

import json

import jsonschema
import pytest

import robotdesc
from robotdesc.report.json import JSON_SCHEMA, SCHEMA_VERSION, render_json

from .report_samples import build_sample


@pytest.fixture
def sample(tmp_path):
    return build_sample(tmp_path)


def test_json_report_fields(sample) -> None:
    results, failures, root = sample
    document = json.loads(render_json(results, failures))
    jsonschema.validate(document, JSON_SCHEMA)
    assert document["schema_version"] == SCHEMA_VERSION == 1
    assert document["tool"] == {"name": "robotdesc", "version": robotdesc.__version__}
    summary = document["summary"]
    assert summary.pop("variants") == [{"target": results[0].target, "args": {},
                                        "variant": {}}]
    assert summary == {"files_checked": 1, "files_not_checked": 1, "error": 1,
                       "warning": 1, "info": 1, "suppressed": 2, "files_read": 1,
                       "suppressed_by": {"inline": 2, "config": 0, "baseline": 0}}
    first = document["diagnostics"][0]
    assert first == {
        "code": "J101", "name": "revolute-without-limit", "severity": "error",
        "message": "revolute joint 'left_elbow' has no <limit>",
        "file": str(root / "arm.xacro"), "line": 3, "column": 2,
        "element": "joint:left_elbow",
        "macro_stack": [{"file": str(root / "robot.urdf.xacro"), "line": 3},
                        {"file": str(root / "robot.urdf.xacro"), "line": 4}],
        "passed_values": [],
        "fix": '<limit lower="-1" upper="1" effort="1" velocity="1"/>',
        "fix_applicability": None,
        "target": str(root / "robot.urdf.xacro"), "variant": {},
        "elements": ["joint:left_elbow"], "variants": [{"args": {}, "variant": {}}],
        "in_all_variants": True,
    }
    assert document["diagnostics"][1]["column"] is None
    assert document["diagnostics"][2]["file"] is None
    assert document["failures"] == [{
        "kind": "ExpansionError", "message": "undefined property 'undefined'",
        "file": str(root / "broken.urdf.xacro"), "line": 2, "column": 3,
        "macro_stack": [{"file": str(root / "robot.urdf.xacro"), "line": 9}],
        "target": str(root / "broken.urdf.xacro"), "variant": {},
    }]


def test_schema_rejects_a_missing_field(sample) -> None:
    results, failures, _ = sample
    document = json.loads(render_json(results, failures))
    del document["diagnostics"][0]["code"]
    try:
        jsonschema.validate(document, JSON_SCHEMA)
    except jsonschema.ValidationError as exc:
        assert "'code' is a required property" in exc.message
    else:  # pragma: no cover
        raise AssertionError("schema accepted a diagnostic without a code")
