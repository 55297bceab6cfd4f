"""One verdict everywhere: lint's suppressions (inline comments, per-file ignores, baseline)
applied to what other commands show about a link's inertia (`inertia --suggest/--write`, the
inertia table of `inertia`, the HTML report and `robotdesc.mesh_inertia`).

A link's inertia is *suppressed* when lint hid a finding of an inertia rule on it and keeps
none of a default-on inertia rule: the maintainer said, with a reason, that the tensor is
meant (the Engineer's track wheels carry their drivetrain's reflected inertia). Such a link
gets no replacement block unless asked for every link, and tables show it as suppressed.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Iterable, Mapping, Sequence

from robotdesc.config import Config
from robotdesc.diagnostics import Diagnostic
from robotdesc.expansion import ExpandOptions
from robotdesc.inertia.table import InertiaRow
from robotdesc.linting.baseline import apply_baseline, read_baseline
from robotdesc.linting.driver import lint_file
from robotdesc.linting.result import LintResult
from robotdesc.rules.catalog import all_rules

#: The rule family whose findings judge a link's `<inertial>`.
INERTIA_FAMILY = "inertia"


def inertia_codes() -> tuple[str, ...]:
    """Every inertia rule's code, the opt-in ones too (a suppression may name one)."""
    return tuple(r.code for r in all_rules() if r.family == INERTIA_FAMILY)


def _link_of(diagnostic: Diagnostic) -> str | None:
    """The link an inertia finding is about (its element is `link:NAME/...`), or None."""
    element = diagnostic.element or ""
    if not element.startswith("link:"):
        return None
    return element[len("link:"):].split("/", 1)[0]


def suppressed_links(hidden: Iterable[Diagnostic], kept: Iterable[Diagnostic]
                     ) -> dict[str, tuple[str, ...]]:
    """Link name -> codes of the inertia findings lint hid on it, for every link with such a
    finding and no kept finding of a default-on inertia rule."""
    codes = set(inertia_codes())
    default_on = {r.code for r in all_rules() if r.family == INERTIA_FAMILY and not r.opt_in}
    found: dict[str, list[str]] = {}
    for diagnostic in hidden:
        link = _link_of(diagnostic)
        if link is not None and diagnostic.code in codes:
            found.setdefault(link, []).append(diagnostic.code)
    blocked = {_link_of(d) for d in kept if d.code in default_on}
    return {link: tuple(dict.fromkeys(found[link])) for link in found if link not in blocked}


def result_verdict(result: LintResult) -> dict[str, tuple[str, ...]]:
    """`suppressed_links` of a lint result (its hidden and kept findings)."""
    return suppressed_links(result.hidden, result.diagnostics)


def inertia_verdict(path: str, config: Config, *, args: Mapping[str, str] | None = None,
                    expand_options: ExpandOptions | None = None,
                    baseline: str | None = None) -> dict[str, tuple[str, ...]]:
    """Lint `path` with the inertia rules (as `lint` would, the config's ignores and
    suppressions applied, then `baseline` when given) and return `suppressed_links`.

    Raises:
        InputError: the file could not be expanded, or the baseline not read.
    """
    result = lint_file(path, config, args=args, expand_options=expand_options,
                       select=inertia_codes())
    if baseline is not None:
        base = os.path.dirname(os.path.abspath(baseline))
        result = apply_baseline([result], read_baseline(baseline), base).results[0]
    return result_verdict(result)


def mark_rows(rows: Sequence[InertiaRow], verdict: Mapping[str, tuple[str, ...]]
              ) -> list[InertiaRow]:
    """The rows with `suppressed` set to the codes lint hid on each link."""
    return [dataclasses.replace(row, suppressed=verdict[row.link]) if row.link in verdict
            else row for row in rows]
