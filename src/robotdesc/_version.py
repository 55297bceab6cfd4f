"""The version of robotdesc (one place; the package and every report read it).

The identity of the code, which keys the caches, is `robotdesc.code_stamp` (it needs hashlib,
which `import robotdesc` and the xacro worker do not).
"""

from __future__ import annotations

__version__ = "0.1.0"
