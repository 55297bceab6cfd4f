"""Read the plain numeric properties of urdf/properties.xacro (shared by the package's scripts)."""

from __future__ import annotations

import re
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent.parent
PROPERTIES = PACKAGE / "urdf" / "properties.xacro"

_PROPERTY = re.compile(r'<xacro:property\s+name="([^"]+)"\s+value="([^"$]+)"\s*/>')


def read_properties(path: Path = PROPERTIES) -> dict[str, float]:
    """The properties of `path` whose value is one plain number (metres, kilograms, radians).

    Vectors ("0.22 0.12 0.06") and expressions ("${-pi}") are left out.
    """
    values: dict[str, float] = {}
    for name, text in _PROPERTY.findall(path.read_text(encoding="utf-8")):
        try:
            values[name] = float(text)
        except ValueError:
            continue
    return values
