"""One edit engine for every command that writes into the user's sources.

fix.py: a `Fix` is data (edits, applicability, reason); index.py: the expanded document and
the attribute changes a fix asks; locate.py: where a change goes in the xacro sources (macro
body, call site, property, or refused on an expression); values.py: only values that change
are rewritten; engine.py: conflicts, the diff, atomic writes refused when a file changed.

Import the submodules (this package imports nothing, so that `robotdesc.edit.fix`, which
the rules and reports use, stays cheap to import).
"""
