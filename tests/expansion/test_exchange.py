"""The parent's side of the worker's pipes (robotdesc/expansion/exchange.py): the answer
arrives whole whatever its size, through a pipe widened where the system allows."""

from __future__ import annotations

import subprocess
import sys

import pytest

from robotdesc.expansion import exchange as exchange_module
from robotdesc.expansion.exchange import _ANSWER_PIPE_BYTES, _widen, exchange

WRITER = ("import sys; data = sys.stdin.buffer.read(); "
          "sys.stdout.buffer.write(data * {times}); sys.stderr.write('note')")


@pytest.mark.parametrize("times", [1, 5_000, 40_000])
def test_the_answer_arrives_whole(times: int) -> None:
    proc = subprocess.Popen([sys.executable, "-c", WRITER.format(times=times)],
                            stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE)
    done = exchange(proc, b"0123456789" * 10, timeout_s=30, answer_cap=1 << 26)
    assert done.out == b"0123456789" * 10 * times
    assert done.err == b"note" and not done.overflow and not done.timed_out


def test_the_answer_pipe_is_widened_where_linux_allows() -> None:
    fcntl = pytest.importorskip("fcntl")
    if not hasattr(fcntl, "F_GETPIPE_SZ"):
        pytest.skip("no F_GETPIPE_SZ here")
    with open("/proc/sys/fs/pipe-max-size") as handle:
        if int(handle.read()) < _ANSWER_PIPE_BYTES:
            pytest.skip("pipes may not be that large here")

    proc = subprocess.Popen([sys.executable, "-c", "pass"], stdout=subprocess.PIPE)
    try:
        _widen(proc.stdout)
        assert fcntl.fcntl(proc.stdout.fileno(), fcntl.F_GETPIPE_SZ) >= _ANSWER_PIPE_BYTES
    finally:
        proc.communicate()


def test_the_switch_interval_comes_back_whatever_order_exchanges_end_in():
    before = sys.getswitchinterval()
    first, second = exchange_module._short_switch_interval(), exchange_module._short_switch_interval()
    first.__enter__()
    second.__enter__()
    assert sys.getswitchinterval() == min(before, exchange_module._SWITCH_INTERVAL_S)
    first.__exit__(None, None, None)
    assert sys.getswitchinterval() == min(before, exchange_module._SWITCH_INTERVAL_S)
    second.__exit__(None, None, None)
    assert sys.getswitchinterval() == before
