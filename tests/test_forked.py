"""A forked child that works beside this process (robotdesc/forked.py): what it writes
arrives, it never writes to this process's streams, and one that is stuck is ended."""

from __future__ import annotations

import logging
import os
import sys
import threading
import time

import pytest

from robotdesc import forked
from robotdesc.forked import Forked, forks_here, read_all, write_all

pytestmark = pytest.mark.skipif(not forks_here(),
                                 reason="robotdesc forks helper processes on Linux only")


def _echo(inbox: int, out: int) -> None:
    data = read_all(inbox, 1 << 20) or b""
    write_all(out, data.upper())


def test_the_child_reads_its_inbox_and_answers() -> None:
    child = Forked(_echo)
    child.send(b"pinocchio" * 10_000)
    assert child.read_to_end(1 << 20) == b"PINOCCHIO" * 10_000
    child.close()
    assert not child.running


def test_the_child_writes_nothing_to_this_process_and_logs_nothing(capfd) -> None:
    def noisy(_inbox: int, out: int) -> None:
        print("from the child")
        sys.stderr.write("to stderr\n")
        logging.getLogger("robotdesc").error("logged in the child")
        write_all(out, b"done")

    child = Forked(noisy)
    child.send(b"")
    assert child.read_to_end(1 << 20) == b"done"
    child.close()
    captured = capfd.readouterr()
    assert "child" not in captured.out + captured.err and "stderr" not in captured.err


def test_a_child_that_makes_no_progress_is_ended(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(forked, "STUCK_S", 0.6)
    monkeypatch.setattr(forked, "_POLL_S", 0.2)
    lock = threading.Lock()
    lock.acquire()  # held in the child too, by no thread: it waits for ever

    def stuck(_inbox: int, _out: int) -> None:
        lock.acquire()

    child = Forked(stuck)
    child.send(b"")
    started = time.monotonic()
    assert child.read(wait=True) == b""  # taken for ended
    assert time.monotonic() - started < 10 and not child.running
    lock.release()


def test_a_child_given_no_input_yet_is_not_stuck(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(forked, "STUCK_S", 0.4)
    monkeypatch.setattr(forked, "_POLL_S", 0.1)
    child = Forked(_echo)
    assert child.read(wait=False) is None
    child.send(b"late")
    assert child.read_to_end(1 << 20) == b"LATE"
    child.close()


def test_each_child_sees_the_end_of_its_inbox_while_others_live() -> None:
    first, second = Forked(_echo), Forked(_echo)  # the second holds no copy of first's inbox
    first.send(b"a")
    assert first.read_to_end(1 << 20) == b"A"
    second.send(b"b")
    assert second.read_to_end(1 << 20) == b"B"
    first.close()
    second.close()
    assert not forked._PARENT_ENDS


def test_a_closed_child_reads_as_ended() -> None:
    child = Forked(_echo)
    child.close()
    assert child.read(wait=True) == b"" and os.getpid() > 0


def test_an_answer_past_the_limit_is_none() -> None:
    child = Forked(_echo)
    child.send(b"x" * 5000)
    assert child.read_to_end(1000) is None
    child.close()
