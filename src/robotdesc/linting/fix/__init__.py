"""`robotdesc lint --fix`: write findings' fixes back into the xacro/URDF sources.

changes.py turns a diagnostic into attribute changes of expanded elements, plan.py finds
where each change goes in the source (a literal, or a macro argument at its call site),
engine.py checks shared locations, builds the fixed files and the diff, and writes them.
"""

from robotdesc.linting.fix.engine import (
    FileFix,
    FixOutcome,
    FixPlan,
    package_root,
    plan_fixes,
    write_fixes,
)

__all__ = ["FileFix", "FixOutcome", "FixPlan", "package_root", "plan_fixes", "write_fixes"]
