"""benchmarks/corpus/split.toml (issue 29's blind protocol): the parts are disjoint, the seeded
draw still gives the blind list whatever is added to the manifest, and the validation part
(issue 29's own held-out repositories) is neither drawn nor tuned on. Reads the manifest only:
no corpus, no network."""

from __future__ import annotations

import importlib
import sys
from pathlib import Path
from types import ModuleType

REPO = Path(__file__).resolve().parents[1]
CORPUS_SCRIPTS = REPO / "benchmarks" / "corpus"


def _blind() -> ModuleType:
    if str(CORPUS_SCRIPTS) not in sys.path:
        sys.path.insert(0, str(CORPUS_SCRIPTS))
    return importlib.import_module("blind")


def test_the_draw_is_unchanged_by_the_validation_part() -> None:
    blind = _blind()
    manifest = blind.run_corpus.load_manifest(blind.run_corpus.DEFAULT_MANIFEST)
    split = blind.load_split()
    assert blind.draw_split(manifest, split) == sorted(split["blind"])


def test_parts_are_disjoint_and_cover_every_case() -> None:
    blind = _blind()
    manifest = blind.run_corpus.load_manifest(blind.run_corpus.DEFAULT_MANIFEST)
    split = blind.load_split()
    validation = set(split["validation"])
    assert not validation & (set(split["blind"]) | set(split["added"]))
    parts = {part: blind.part_cases(manifest, split, part) for part in blind.PARTS}
    names = [case.name for cases in parts.values() for case in cases]
    assert sorted(names) == sorted(case.name for case in manifest.cases)
    assert {case.repository for case in parts["validation"]} == validation
    assert not {case.repository for case in parts["tuning"]} & validation


def test_validation_is_a_part_of_the_command_line() -> None:
    options = _blind().parse_args(["sheet", "--part", "validation", "--label", "validation"])
    assert options.part == "validation"
