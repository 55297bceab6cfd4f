"""Rules with and without options, and a file writer, shared by the config tests."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from robotdesc.diagnostics import Severity
from robotdesc.rules.registry import Rule


@dataclass(frozen=True)
class DepthOptions:
    max_depth: int = 16
    ratio: float = 1.0
    names: tuple[str, ...] = ()
    mode: Literal["fast", "slow"] = "fast"
    limit: float | None = None

    def __post_init__(self) -> None:
        if self.max_depth < 1:
            raise ValueError("max_depth must be at least 1")


def _check(robot, ctx):
    """Does nothing."""
    return ()


RULES = [
    Rule("J101", "revolute-without-limit", "joints", Severity.ERROR, _check),
    Rule("J107", "axis-not-normalised", "joints", Severity.WARNING, _check),
    Rule("S001", "no-root-link", "structure", Severity.ERROR, _check),
    Rule("X101", "deep-macro-recursion", "expansion", Severity.WARNING, _check, DepthOptions),
]


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path
