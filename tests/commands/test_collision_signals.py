"""SIGTERM during `robotdesc collision`: the workers are stopped and nothing prints a
traceback (a worker that outlives its parent finds a closed pipe and ends quietly)."""

from __future__ import annotations

import multiprocessing
import os
import signal

import pytest

from robotdesc.collision.worker import _child
from robotdesc.commands.collision import _terminated_quietly


def _double(value: int) -> int:
    return 2 * value


def test_sigterm_ends_the_command_with_exit_143(capsys) -> None:
    before = signal.getsignal(signal.SIGTERM)
    with pytest.raises(SystemExit) as ended:
        with _terminated_quietly():
            os.kill(os.getpid(), signal.SIGTERM)  # its handler runs before the next line
    assert ended.value.code == 143
    assert capsys.readouterr().err == "robotdesc: terminated\n"
    assert signal.getsignal(signal.SIGTERM) is before


def test_a_worker_whose_parent_is_gone_ends_quietly() -> None:
    reader, writer = multiprocessing.Pipe(duplex=False)
    reader.close()  # the parent was terminated
    _child(_double, 21, writer)  # no BrokenPipeError
