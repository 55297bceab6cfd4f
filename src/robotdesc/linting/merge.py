"""One finding per problem per source location.

A target linted in several variants (config `targets` with other arguments, a matrix) finds a
problem in a shared macro once per variant, and a macro line that makes several elements
(an arm joint macro called for the shoulder and the elbow) once per element. Every report
merges the findings of one target that agree in code, severity, file, line, column and message
(the element's name aside) into one `MergedFinding` that lists its elements and the variants
it occurs in; a finding present in only some variants names them.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass

from robotdesc.diagnostics import Diagnostic
from robotdesc.linting.matrix import variant_label
from robotdesc.linting.result import LintResult

#: A linted variant: its xacro arguments (config target and command line) or, without
#: arguments, its matrix variant; () is the file's defaults.
RunArgs = tuple[tuple[str, str], ...]

#: Variants listed by name in a merged finding's note; more are counted.
LISTED_VARIANTS = 4
#: Elements listed by name under a merged finding; more are counted.
LISTED_ELEMENTS = 8


@dataclass(frozen=True)
class MergedFinding:
    """One problem at one source location of one target, over its elements and variants.

    Attributes:
        diagnostic: the first occurrence (its message names the first element).
        target: the linted (top-level) file.
        elements: the distinct elements the problem was found on, in order of appearance.
        variants: the variants it occurs in (their `RunArgs`), in the order they were linted.
        variant_matrix: the matrix variant of each entry of `variants` (() when none).
        runs: how many variants of `target` were linted.
        occurrences: every diagnostic merged here (one per element and variant).
    """

    diagnostic: Diagnostic
    target: str
    elements: tuple[str, ...]
    variants: tuple[RunArgs, ...]
    variant_matrix: tuple[RunArgs, ...]
    runs: int
    occurrences: tuple[Diagnostic, ...]

    @property
    def in_all_variants(self) -> bool:
        """Whether every linted variant of the target has this finding."""
        return len(self.variants) >= self.runs

    def variant_note(self) -> str:
        """Which variants, when not all: " (only in variant [with_gripper=false])", else
        ""."""
        if self.in_all_variants:
            return ""
        labels = self._labels()
        shown = ", ".join(labels[:LISTED_VARIANTS])
        more = f" and {len(labels) - LISTED_VARIANTS} more" if len(labels) > LISTED_VARIANTS \
            else ""
        return f" (only in variant{'s' if len(labels) > 1 else ''} {shown}{more})"

    def elements_text(self) -> str:
        """"6 elements: joint:a, joint:b, ..." ("" for one element); past LISTED_ELEMENTS,
        the rest are counted."""
        if len(self.elements) <= 1:
            return ""
        shown = ", ".join(self.elements[:LISTED_ELEMENTS])
        more = len(self.elements) - LISTED_ELEMENTS
        return f"{len(self.elements)} elements: {shown}" + (f", ... {more} more" if more > 0
                                                            else "")

    def _labels(self) -> list[str]:
        """The variants it occurs in, as `run_label` names them."""
        return [run_label(args, matrix) for args, matrix
                in zip(self.variants, self.variant_matrix)]

    def variants_text(self) -> str:
        """The variants as one line: "in all 3 variants: [default arguments], ..." or
        "in 2 of 3 variants: ..." ("" when the target was linted once)."""
        if self.runs <= 1:
            return ""
        labels = self._labels()
        shown = ", ".join(labels[:LISTED_VARIANTS])
        more = f", ... {len(labels) - LISTED_VARIANTS} more" if len(labels) > LISTED_VARIANTS \
            else ""
        count = f"all {self.runs}" if self.in_all_variants else f"{len(labels)} of {self.runs}"
        return f"in {count} variants: {shown}{more}"


def run_label(args: RunArgs, matrix: RunArgs = ()) -> str:
    """A variant's name: its matrix label (`[side=left]`), else its arguments
    (`[with_gripper=false]`), else `[default arguments]`."""
    if matrix:
        return variant_label(matrix)
    return variant_label(args) if args else "[default arguments]"


def run_args(result: LintResult) -> RunArgs:
    """The identity of a linted variant: its arguments, else its matrix variant."""
    return tuple(result.args or result.variant)


def element_name(element: str) -> str:
    """The name inside an element key: "joint:elbow" -> "elbow", "link:a/visual[0]" -> "a"."""
    return element.split(":", 1)[-1].split("/", 1)[0] if ":" in element else ""


def message_key(diagnostic: Diagnostic) -> str:
    """The message with the element's name taken out (findings of one macro line on two
    elements then agree)."""
    name = element_name(diagnostic.element)
    if not name:
        return diagnostic.message
    return re.sub(rf"(?<![\w-]){re.escape(name)}(?![\w-])", "\0", diagnostic.message)


def finding_key(diagnostic: Diagnostic, target: str) -> tuple[object, ...]:
    """What two occurrences of one problem share."""
    span = diagnostic.where.span if diagnostic.where else None
    return (target, diagnostic.code, diagnostic.severity,
            span.path if span else "", span.line if span else 0, span.col if span else 0,
            message_key(diagnostic))


def merge_findings(results: Sequence[LintResult]) -> list[MergedFinding]:
    """The findings of `results` (`LintResult`s), merged per target and source location, in
    the order of their first occurrence."""
    runs: dict[str, int] = {}
    for result in results:
        runs[result.target] = runs.get(result.target, 0) + 1
    groups: dict[tuple[object, ...], list[tuple[Diagnostic, RunArgs, RunArgs]]] = {}
    for result in results:
        args = run_args(result)
        matrix = tuple(getattr(result, "variant", ()))
        for diagnostic in result.diagnostics:
            groups.setdefault(finding_key(diagnostic, result.target), []).append(
                (diagnostic, args, matrix))
    merged: list[MergedFinding] = []
    for key, entries in groups.items():
        target = str(key[0])
        variants = list(dict.fromkeys((args, matrix) for _, args, matrix in entries))
        merged.append(MergedFinding(
            diagnostic=entries[0][0], target=target,
            elements=tuple(dict.fromkeys(d.element for d, _, _ in entries if d.element)),
            variants=tuple(args for args, _ in variants),
            variant_matrix=tuple(matrix for _, matrix in variants),
            runs=runs[target], occurrences=tuple(d for d, _, _ in entries)))
    return merged
