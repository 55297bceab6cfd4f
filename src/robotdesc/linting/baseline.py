"""Baselines: record today's findings, then report only new ones (adopting robotdesc on a
package that already has findings).

A finding is identified by its target (path relative to the baseline file, plus the matrix
variant), rule code, element and message — not by its line, so edits above a finding do not
make it new. Identical findings are counted: a third copy of a finding recorded twice is
new. The file is JSON, sorted, so that it diffs well under version control::

    {"robotdesc_baseline": 1,
     "findings": [{"target": "urdf/robot.urdf.xacro", "code": "J101",
                   "element": "joint:elbow", "message": "...", "count": 2}]}
"""

from __future__ import annotations

import dataclasses
import json
import os
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass

from robotdesc.diagnostics import Diagnostic
from robotdesc.errors import InputError
from robotdesc.linting.result import LintResult
from robotdesc.linting.targets import target_name
from robotdesc.source import Span

BASELINE_VERSION = 1

#: (target, code, element, message)
Key = tuple[str, str, str, str]
#: One recorded finding as JSON: the four parts of its key and its count.
Entry = dict[str, str | int]
#: The baseline file as JSON: its version and its entries.
Document = dict[str, int | list[Entry]]


@dataclass(frozen=True)
class BaselineOutcome:
    """What applying a baseline did.

    Attributes:
        results: the results with baselined findings removed.
        matched: how many findings the baseline hid.
        stale: how many recorded findings no longer occur (the baseline can be rewritten).
    """

    results: tuple[LintResult, ...]
    matched: int
    stale: int


def finding_key(diagnostic: Diagnostic, result: LintResult, base: str) -> Key:
    """The line-free identity of a finding, relative to the baseline's directory `base`."""
    prefix = os.path.abspath(base) + os.sep
    return (target_name(result.target, result.variant, base), diagnostic.code,
            diagnostic.element, diagnostic.message.replace(prefix, ""))


def baseline_document(results: Sequence[LintResult], base: str) -> Document:
    """The baseline of `results` as a JSON-ready dict (paths relative to `base`)."""
    counts = Counter(finding_key(d, r, base) for r in results for d in r.diagnostics)
    findings: list[Entry] = [{"target": t, "code": c, "element": e, "message": m, "count": n}
                             for (t, c, e, m), n in sorted(counts.items())]
    return {"robotdesc_baseline": BASELINE_VERSION, "findings": findings}


def render_baseline(results: Sequence[LintResult], path: str) -> str:
    """The baseline file's text for `results`, to be written at `path`."""
    document = baseline_document(results, os.path.dirname(os.path.abspath(path)))
    return json.dumps(document, indent=2, ensure_ascii=False) + "\n"


def read_baseline(path: str) -> Counter[Key]:
    """The recorded findings of a baseline file, counted by key.

    Raises:
        InputError: the file cannot be read or is not a robotdesc baseline.
    """
    try:
        with open(path, encoding="utf-8") as handle:
            document = json.load(handle)
    except OSError as exc:
        raise InputError(f"cannot read baseline: {exc.strerror}", Span(path)) from None
    except json.JSONDecodeError as exc:
        raise InputError(f"baseline is not valid JSON: {exc.msg}",
                         Span(path, exc.lineno)) from None
    except UnicodeDecodeError as exc:
        raise InputError(f"baseline is not valid JSON: {exc}", Span(path)) from None
    return baseline_counts(document, path)


def baseline_counts(document: object, path: str) -> Counter[Key]:
    """The recorded findings of a baseline document (as read from `path`), counted by key.

    Raises:
        InputError: the document is not a robotdesc baseline.
    """
    if not isinstance(document, dict) or document.get("robotdesc_baseline") != BASELINE_VERSION:
        raise InputError("not a robotdesc baseline (version "
                         f"{BASELINE_VERSION}); write one with --write-baseline", Span(path))
    counts: Counter[Key] = Counter()
    for entry in document.get("findings", []):
        try:
            key: Key = (entry["target"], entry["code"], entry["element"], entry["message"])
            count = int(entry.get("count", 1))
        except (TypeError, KeyError, ValueError):
            raise InputError(f"baseline entry is malformed: {entry!r}", Span(path)) from None
        counts[key] += count
    return counts


def apply_baseline(results: Sequence[LintResult], baseline: Counter[Key],
                   base: str) -> BaselineOutcome:
    """Remove the findings the baseline records (as many of each as it counts).

    Args:
        results: the lint results.
        baseline: counts by key, as `read_baseline` returns them.
        base: the baseline file's directory (target paths are relative to it).
    """
    remaining = Counter(baseline)
    kept_results: list[LintResult] = []
    matched = 0
    for result in results:
        kept: list[Diagnostic] = []
        hidden: list[Diagnostic] = []
        for diagnostic in result.diagnostics:
            key = finding_key(diagnostic, result, base)
            if remaining[key] > 0:
                remaining[key] -= 1
                matched += 1
                hidden.append(diagnostic)
            else:
                kept.append(diagnostic)
        kept_results.append(dataclasses.replace(result, diagnostics=tuple(kept),
                                                hidden=result.hidden + tuple(hidden)))
    return BaselineOutcome(tuple(kept_results), matched, sum(remaining.values()))
