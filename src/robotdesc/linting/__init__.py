"""Linting: run the selected rules over a description and collect diagnostics.

`lint_file` (driver.py) is the pipeline; rules/select.py chooses rules, suppress.py reads inline
`<!-- robotdesc: ignore CODE -->` comments, targets.py turns command-line paths into
targets (matrix.py: argument variants), parallel.py lints many targets across processes,
baseline.py hides findings already recorded.
"""

from __future__ import annotations

from robotdesc.lazy import lazy_exports

_LAZY = {"lint_file": "driver", "LintResult": "result", "RuleCrashed": "result",
         "LintFailure": "result",
         "discover_targets": "targets", "LintTarget": "targets", "lint_targets": "parallel"}

__all__ = ["LintFailure", "LintResult", "LintTarget", "RuleCrashed", "discover_targets",
           "lint_file", "lint_targets"]


__getattr__, __dir__ = lazy_exports(__name__, _LAZY)
