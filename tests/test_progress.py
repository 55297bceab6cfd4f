"""robotdesc.progress: a plain line every period when piped, nothing when quiet or quick."""

from __future__ import annotations

import io
import time

from robotdesc.progress import Progress


def test_plain_lines_every_period_when_piped() -> None:
    out = io.StringIO()
    with Progress("srdf", total=100, unit="samples", stream=out, period=0.05) as bar:
        bar.update(25, detail="40 pairs")
        time.sleep(0.18)
    lines = out.getvalue().splitlines()
    assert len(lines) >= 2
    assert lines[0].startswith("robotdesc: srdf: 25 of 100 samples (25 %), 0 s; 40 pairs")


def test_quick_and_quiet_runs_write_nothing() -> None:
    out = io.StringIO()
    with Progress("lint", total=3, stream=out, period=5.0) as bar:
        bar.advance()
    with Progress("lint", total=3, stream=out, period=0.01, quiet=True) as bar:
        bar.advance()
        time.sleep(0.05)
    assert out.getvalue() == ""


def test_unknown_total_says_working() -> None:
    bar = Progress("info", stream=io.StringIO())
    assert bar.line().startswith("robotdesc: info: working, 0 s")
