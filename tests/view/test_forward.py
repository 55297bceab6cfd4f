"""The view's `--q name=value` assignments (forward kinematics: tests/model/test_forward.py)."""

from __future__ import annotations

import pytest

from robotdesc.errors import UsageError
from robotdesc.view.forward import parse_assignments


def test_parse_assignments() -> None:
    assert parse_assignments(["a=1.5", " b = -2 "]) == {"a": 1.5, "b": -2.0}
    for bad in ("a", "=1", "a=x"):
        with pytest.raises(UsageError, match="expected JOINT=VALUE"):
            parse_assignments([bad])
