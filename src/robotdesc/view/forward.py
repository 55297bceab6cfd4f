"""What is view-specific about poses: `--q name=value` assignments of `robotdesc view`,
`robotdesc report` and `robotdesc info`. Forward kinematics itself (configurations, mimic joints, joint motions,
link poses) is `robotdesc.model.tree`.
"""

from __future__ import annotations

import math

from robotdesc.errors import UsageError


def parse_assignments(items: list[str] | tuple[str, ...]) -> dict[str, float]:
    """`name=value` strings (from `--q`) to a dict; radians or metres.

    Raises:
        UsageError: an item is not `name=number` (a finite number).
    """
    values: dict[str, float] = {}
    for item in items:
        name, sep, text = item.partition("=")
        try:
            if not sep or not name.strip():
                raise ValueError
            value = float(text)
            if not math.isfinite(value):
                raise ValueError
            values[name.strip()] = value
        except ValueError:
            raise UsageError(f"--q '{item}': expected JOINT=VALUE (radians or metres)") from None
    return values
