"""The rule index: what `robotdesc rules` and `robotdesc rule CODE` print, read from
`index.json` beside this module instead of importing every rule module (which costs about
100 ms of imports: the model, meshes and expansion packages they use).

The index is generated from the registry (`python -m robotdesc.rules.docs --index`, see
`robotdesc.rules.docs`) and records the SHA-256 of the rule package's sources it was made
from; when those sources changed since (a rule added, an option's default edited), the index
is not used and the caller asks the registry itself. A test keeps the shipped index current.
"""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Sequence
from typing import TYPE_CHECKING, NamedTuple

if TYPE_CHECKING:
    from robotdesc.rules.registry import Rule

INDEX_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "index.json")
#: Bytes an index may have (it is a few hundred kB).
_MAX_BYTES = 4 << 20


#: One rule as `robotdesc rules` lists it: code, name, family, severity, default, summary.
Row = tuple[str, str, str, str, str, str]


class RuleIndex(NamedTuple):
    """What the two commands print, per rule (a named tuple, not a dataclass: this module
    is on the start-up path of `robotdesc rules`, and `dataclasses` costs 4 ms there).

    Attributes:
        rows: (code, name, family, severity, default "on"/"off", summary) per rule, sorted
            by code.
        help: the text of `robotdesc rule CODE`, by code.
    """

    rows: tuple[Row, ...]
    help: dict[str, str]

    def find(self, code_or_name: str) -> str | None:
        """The help of the rule with this code (case-insensitive) or kebab-case name."""
        key = code_or_name.strip()
        if key.upper() in self.help:
            return self.help[key.upper()]
        code = next((row[0] for row in self.rows if row[1] == key), None)
        return None if code is None else self.help[code]


class RuleName(NamedTuple):
    """A rule's code and kebab-case name, as selectors match them."""

    code: str
    name: str


def known_names() -> Sequence[RuleName] | Sequence[Rule]:
    """Every rule's code and name: from the shipped index while it is current (reading it
    costs a few ms), else from the registry (every rule module imported, about 50-100 ms):
    enough to check `--select`, `--ignore` and a config's selectors before a lint starts."""
    index = read_index()
    if index is not None:
        return [RuleName(row[0], row[1]) for row in index.rows]
    from robotdesc.rules.catalog import all_rules  # every rule module: only when stale

    return all_rules()


def sources_digest() -> str:
    """The SHA-256 of the rule package's Python sources (names and bytes, sorted by name)."""
    folder = os.path.dirname(os.path.abspath(__file__))
    digest = hashlib.sha256()
    for name in sorted(os.listdir(folder)):
        if name.endswith(".py"):
            with open(os.path.join(folder, name), "rb") as stream:
                digest.update(name.encode() + b"\0" + stream.read() + b"\0")
    return digest.hexdigest()


def index_document(rows: list[Row], help: dict[str, str]) -> str:
    """The text of `index.json` for these rows and help texts, stamped with the sources."""
    return json.dumps({"sources": sources_digest(), "rows": rows, "help": help},
                      indent=1, ensure_ascii=False, sort_keys=True) + "\n"


def read_index(path: str = INDEX_FILE) -> RuleIndex | None:
    """The shipped index, or None when it is missing, malformed or made from other sources."""
    try:
        with open(path, "rb") as stream:
            data = json.loads(stream.read(_MAX_BYTES))
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("sources") != sources_digest():
        return None
    rows, help = data.get("rows"), data.get("help")
    if not isinstance(rows, list) or not isinstance(help, dict):
        return None
    if not all(isinstance(row, list) and len(row) == 6 and all(isinstance(c, str) for c in row)
               for row in rows):
        return None
    if not all(isinstance(k, str) and isinstance(v, str) for k, v in help.items()) \
            or {row[0] for row in rows} != set(help):
        return None
    return RuleIndex(tuple((r[0], r[1], r[2], r[3], r[4], r[5]) for r in rows), dict(help))
