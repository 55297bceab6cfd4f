"""One edit engine for every command that writes into the user's sources.

fix.py: a `Fix` is data (edits, applicability, reason); index.py: the expanded document and
the attribute changes a fix asks; locate.py: where a change goes in the xacro sources (macro
body, call site, property, or refused on an expression); values.py: only values that change
are rewritten; engine.py: conflicts, the diff, atomic writes refused when a file changed.
"""

from robotdesc.edit.engine import (
    FileChange,
    apply_edits,
    apply_fixes,
    resolve_conflicts,
    unified_diff,
    write_changes,
)
from robotdesc.edit.fix import Applicability, Edit, Fix
from robotdesc.edit.index import AttributeChange, Changes, ExpandedIndex, Refused
from robotdesc.edit.locate import SourceCache, changes_fix, locate, package_folder

__all__ = ["Applicability", "AttributeChange", "Changes", "Edit", "ExpandedIndex",
           "FileChange", "Fix", "Refused", "SourceCache", "apply_edits", "apply_fixes",
           "changes_fix", "locate", "package_folder", "resolve_conflicts", "unified_diff", "write_changes"]
