"""What is view-specific about poses: `--q name=value` assignments of `robotdesc view` and
`robotdesc report`. Forward kinematics itself (configurations, mimic joints, joint motions,
link poses) is `robotdesc.model.tree`.
"""

from __future__ import annotations

from robotdesc.errors import UsageError


def parse_assignments(items: list[str] | tuple[str, ...]) -> dict[str, float]:
    """`name=value` strings (from `--q`) to a dict; radians or metres.

    Raises:
        UsageError: an item is not `name=number`.
    """
    values: dict[str, float] = {}
    for item in items:
        name, sep, text = item.partition("=")
        try:
            if not sep or not name.strip():
                raise ValueError
            values[name.strip()] = float(text)
        except ValueError:
            raise UsageError(f"--q '{item}': expected JOINT=VALUE (radians or metres)") from None
    return values
