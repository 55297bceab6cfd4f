"""The worker's audit hook (`robotdesc.expansion.sandbox.Guard`)."""

from __future__ import annotations

import pytest

from robotdesc.expansion import sandbox


def test_the_events_let_through_at_once_are_none_safe_mode_refuses() -> None:
    assert "open" not in sandbox._FREQUENT_EVENTS
    assert not [event for event in sandbox._FREQUENT_EVENTS
                if event.startswith(sandbox._FORBIDDEN_EVENTS)]


@pytest.mark.parametrize("event", ["os.system", "subprocess.Popen", "socket.connect",
                                   "os.exec", "ctypes.dlopen"])
def test_an_armed_guard_refuses_a_forbidden_event(event: str) -> None:
    guard = sandbox.Guard(safe=True, armed=True)
    with pytest.raises(sandbox.Forbidden):
        guard(event, ())
    for frequent in sandbox._FREQUENT_EVENTS:
        guard(frequent, ())  # let through
