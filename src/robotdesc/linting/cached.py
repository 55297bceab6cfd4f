"""One target's answer from the whole-result cache (`robotdesc.linting.result_cache`), under
the key its lint would store: what `robotdesc lint` asks before importing any of the lint
machinery (a warm lint is a cache read, issue 31)."""

from __future__ import annotations

import dataclasses
import logging
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

from robotdesc.linting import result_cache
from robotdesc.linting.result import LintResult
from robotdesc.linting.targets import LintTarget

if TYPE_CHECKING:
    from robotdesc.expansion import ExpandOptions

log = logging.getLogger(__name__)


def target_key(target: LintTarget, args: Mapping[str, str], expand_options: ExpandOptions | None,
               select: Sequence[str] | None,
               ignore: Sequence[str]) -> result_cache.CacheKey | None:
    """The whole-result cache key of one target (its own settings, as its lint stores it)."""
    return result_cache.result_key(
        target.path, config=target.config, args={**dict(target.args), **dict(args)},
        variant=target.variant, select=select, ignore=tuple(ignore),
        expand_options=expand_options)


def cached_result(target: LintTarget, args: Mapping[str, str], expand_options: ExpandOptions | None,
                  select: Sequence[str] | None, ignore: Sequence[str]) -> LintResult | None:
    """The stored result of `target` when none of its inputs changed (else None)."""
    hit = result_cache.load(target_key(target, args, expand_options, select, ignore),
                            target.path)
    if hit is None:
        return None
    log.info("%s: unchanged since the last lint (result cache)", target.name())
    return dataclasses.replace(hit, variant=target.variant)
