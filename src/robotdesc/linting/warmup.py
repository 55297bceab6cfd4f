"""What a cold lint does while the xacro worker expands (`expand_file(while_expanding=)`):
it imports what the lint needs after the expansion (`import_ahead`, `lint_imports`), and
where the rules need no more of Pinocchio than its verdict (`pinocchio_in_child`), it forks
the child that imports Pinocchio and will decide on the model (`robotdesc.kinematics.verdict`).
The worker has its job by then, so nothing here delays it; none of it happens when the
expansion comes from its cache or the file is a plain URDF.

An import that fails here is forgotten: the lint imports the module again where it needs it,
and fails there exactly as it would have without this (Python does not keep a failed module).
"""

from __future__ import annotations

import importlib
import importlib.util
import logging
import sys
from collections.abc import Iterable, Iterator, Sequence

from robotdesc.expansion.launch import more_expected
from robotdesc.forked import forks_here
from robotdesc.kinematics.verdict import verdict_started
from robotdesc.rules.registry import Rule
from robotdesc.rules.select import select_rules

log = logging.getLogger(__name__)

#: The needs of a rule that asks Pinocchio only whether the model builds (K101).
VERDICT_ONLY = frozenset({"pinocchio"})
#: What the parse and the rules import (lxml with the model parser, every rule module).
_ALWAYS = ("robotdesc.model.parse", "robotdesc.rules.catalog")
#: What reading meshes imports: numpy and the readers, the summary.
_MESHES = ("robotdesc.mesh.summary",)
#: What summarizing meshes may import when the summaries are computed (no mesh cache, or an
#: empty one): pycollada for .dae files; last, since it may not be needed at all, and not
#: where a forked child shares the summaries (`robotdesc.mesh.prefetch`: the COLLADA files
#: are the child's, which imports it). (The hull of an open surface is numpy's,
#: `robotdesc.mesh.hull`: a lint never imports scipy.)
_MESH_ANALYSIS = ("collada",)


def import_ahead(plan: Iterable[str]) -> None:
    """Import the modules `plan` yields (it may import to decide); a plan or an import that
    fails is only logged."""
    try:
        for name in plan:
            _import(name)
    except Exception as error:  # a plan that fails: the lint decides again itself
        log.debug("importing ahead stopped: %s: %s", type(error).__name__, error)


def _import(name: str) -> None:
    """Import `name` when it is installed and not imported yet; a failure is only logged
    (the lint imports it again where it needs it)."""
    if name in sys.modules:
        return
    try:
        if importlib.util.find_spec(name) is not None:
            importlib.import_module(name)
    except Exception as error:
        log.debug("importing %s ahead failed: %s: %s", name, type(error).__name__, error)


def lint_imports(select: Sequence[str] | None, ignore: Sequence[str],
                 analyze_meshes: bool) -> Iterator[str]:
    """The modules a lint imports after its expansion, most certainly needed first.

    Args:
        select, ignore: the selection that applies (as `select_rules` takes it).
        analyze_meshes: mesh files will be summarized, not read from a cache (none, or an
            empty one): pycollada may be needed.
    """
    yield from _ALWAYS
    from robotdesc.rules.catalog import all_rules

    rules = select_rules(all_rules(), select, ignore)
    needs = {need for rule in rules for need in rule.needs}
    if "meshes" in needs:
        yield from _MESHES
    if "pinocchio" in needs and not pinocchio_in_child(rules):
        yield "pinocchio"
    if "meshes" in needs and analyze_meshes and not forks_here():
        yield from _MESH_ANALYSIS  # else the child that shares the summaries imports them


def pinocchio_in_child(rules: Iterable[Rule]) -> bool:
    """Whether the rules' use of Pinocchio is decided by a forked child
    (`robotdesc.kinematics.verdict`): every selected rule that needs Pinocchio needs nothing
    else (it asks only whether the model builds: K101), this platform forks, and this
    process lints one xacro target (no child asked before, no more expansions expected:
    several targets in one process import Pinocchio once, here). This process then imports
    no Pinocchio."""
    return bool(verdict_users(rules)) and forks_here() and not verdict_started() \
        and not more_expected()


def verdict_users(rules: Iterable[Rule]) -> list[Rule]:
    """The rules that need Pinocchio, when each needs no more than its verdict on the model
    (`VERDICT_ONLY`: K101); none when another needs a model of its own."""
    users = [rule for rule in rules if "pinocchio" in rule.needs]
    return users if all(rule.needs == VERDICT_ONLY for rule in users) else []
