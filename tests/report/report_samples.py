"""Shared report inputs: a result with three diagnostics in real files, and one failure.

(Not a conftest.py: tests/conftest.py is imported as `conftest` by other tests.)
"""

from __future__ import annotations

from pathlib import Path

from robotdesc.diagnostics import Diagnostic, Severity
from robotdesc.errors import ExpansionError
from robotdesc.linting.result import LintFailure, LintResult
from robotdesc.source import Provenance, Span

MACRO = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm" params="prefix">
\t<joint name="${prefix}elbow" type="revolute">
    </joint>
  </xacro:macro>
</robot>
"""
TOP = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="arm.xacro"/>
  <xacro:arm prefix="left_"/>
  <xacro:arm prefix="right_"/>
  <link name="base"/>
</robot>
"""


def build_sample(tmp_path: Path) -> tuple[list[LintResult], list[LintFailure], Path]:
    """Write the sources to `tmp_path`; return (results, failures, tmp_path)."""
    macro, top = tmp_path / "arm.xacro", tmp_path / "robot.urdf.xacro"
    macro.write_text(MACRO)
    top.write_text(TOP)
    in_macro = Provenance(Span(str(macro), 3, 2), (Span(str(top), 3), Span(str(top), 4)))
    diagnostics = (
        Diagnostic("J101", "revolute-without-limit", Severity.ERROR,
                   "revolute joint 'left_elbow' has no <limit>", in_macro, "joint:left_elbow",
                   '<limit lower="-1" upper="1" effort="1" velocity="1"/>', str(top)),
        Diagnostic("S003", "link-name-case-clash", Severity.WARNING, "link 'base' clashes",
                   Provenance(Span(str(top), 5)), "link:base", None, str(top)),
        Diagnostic("X001", "empty-robot", Severity.INFO, "note", None, "", None, str(top)),
    )
    result = LintResult(str(top), diagnostics, suppressed=2)
    broken = tmp_path / "broken.urdf.xacro"
    broken.write_text("<robot>\n  <link name='${undefined}'/>\n</robot>\n")
    failure = LintFailure(str(broken), ExpansionError(
        "undefined property 'undefined'", Span(str(broken), 2, 3), (Span(str(top), 9),)))
    return [result], [failure], tmp_path
