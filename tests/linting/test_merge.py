"""Merging findings over variants and elements: one per problem and source location."""

from __future__ import annotations

from robotdesc.diagnostics import Diagnostic, Severity
from robotdesc.linting.merge import element_name, merge_findings, message_key
from robotdesc.linting.result import LintResult
from robotdesc.source import Provenance, Span

ARM = Span("/pkg/urdf/arm.xacro", 17, 7)


def _limit(joint: str, span: Span = ARM, low: str = "0.5") -> Diagnostic:
    return Diagnostic("J103", "limit-lower-above-upper", Severity.ERROR,
                      f"joint '{joint}' lower limit {low} is above its upper limit -0.5",
                      Provenance(span), element=f"joint:{joint}", target="/pkg/robot.xacro")


def _result(*diagnostics: Diagnostic, args=()) -> LintResult:
    return LintResult("/pkg/robot.xacro", tuple(diagnostics), args=args)


def test_one_macro_line_over_elements_and_variants_is_one_finding() -> None:
    results = [_result(_limit("elbow"), _limit("shoulder"), args=args)
               for args in ((), (("wheels", "18"),), (("with_gripper", "false"),))]
    (finding,) = merge_findings(results)
    assert finding.elements == ("joint:elbow", "joint:shoulder")
    assert finding.in_all_variants and finding.runs == 3 and len(finding.occurrences) == 6
    assert finding.variant_note() == ""
    assert finding.variants_text() == ("in all 3 variants: [default arguments], [wheels=18], "
                                       "[with_gripper=false]")


def test_a_finding_in_some_variants_says_which() -> None:
    results = [_result(), _result(_limit("elbow"), args=(("with_gripper", "false"),))]
    (finding,) = merge_findings(results)
    assert not finding.in_all_variants
    assert finding.variant_note() == " (only in variant [with_gripper=false])"


def test_other_lines_columns_or_numbers_stay_apart() -> None:
    elsewhere = Span(ARM.path, 18, 7)
    merged = merge_findings([_result(_limit("elbow"), _limit("shoulder", elsewhere),
                                     _limit("wrist", low="0.7"))])
    assert [f.elements for f in merged] == [("joint:elbow",), ("joint:shoulder",),
                                            ("joint:wrist",)]


def test_the_element_name_is_taken_out_of_the_message_as_a_word() -> None:
    assert element_name("link:base/visual[0]") == "base" and element_name("") == ""
    assert message_key(_limit("a")) == "joint '\0' lower limit 0.5 is above its upper limit -0.5"


def test_long_element_lists_are_counted() -> None:
    (finding,) = merge_findings([_result(*(_limit(f"wheel_{n}") for n in range(20)))])
    assert finding.elements_text() == ("20 elements: " + ", ".join(
        f"joint:wheel_{n}" for n in range(8)) + ", ... 12 more")
