"""Progress of long commands on stderr: a rich bar on a terminal, a plain line every few
seconds when stderr is piped (CI logs), nothing with `-q`.

    with Progress("srdf", total=10000, unit="samples") as progress:
        progress.update(2500, detail="312 pairs sampled")

A run that ends before the first period prints no plain line, so quick commands stay quiet.
The commands make one with `progress_for(ns, ...)` (which reads `--quiet`).
"""

from __future__ import annotations

import os
import sys
import threading
import time
from typing import Any, TextIO

#: Seconds between plain lines when stderr is not a terminal.
PLAIN_PERIOD_S = 5.0


def _is_terminal(stream: TextIO) -> bool:
    if os.environ.get("ROBOTDESC_PROGRESS") == "plain":
        return False
    return bool(getattr(stream, "isatty", lambda: False)())


def _duration(seconds: float) -> str:
    seconds = int(seconds)
    return f"{seconds // 60} min {seconds % 60:02d} s" if seconds >= 60 else f"{seconds} s"


class Progress:
    """One task's progress (a context manager; `update` and `advance` are thread-safe).

    Args:
        label: what runs ("srdf", "lint").
        total: the amount of work (None: unknown; the bar then shows the elapsed time).
        unit: what is counted ("samples", "targets"), for the plain lines.
        stream: where to write (default: stderr).
        quiet: write nothing.
        period: seconds between plain lines when `stream` is not a terminal.
    """

    def __init__(self, label: str, *, total: float | None = None, unit: str = "",
                 stream: TextIO | None = None, quiet: bool = False,
                 period: float = PLAIN_PERIOD_S) -> None:
        self.label, self.unit, self.period, self.quiet = label, unit, period, quiet
        self.stream = stream if stream is not None else sys.stderr
        self.total, self.done, self.detail = total, 0.0, ""
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._bar: Any = None
        self._task: Any = None
        self._started = time.monotonic()

    def __enter__(self) -> Progress:
        self._started = time.monotonic()
        if self.quiet:
            return self
        if _is_terminal(self.stream):
            from rich.console import Console
            from rich.progress import BarColumn, MofNCompleteColumn, TextColumn, TimeElapsedColumn
            from rich.progress import Progress as Bar

            self._bar = Bar(TextColumn(self.label), BarColumn(), MofNCompleteColumn(),
                            TimeElapsedColumn(), TextColumn("{task.description}"),
                            console=Console(file=self.stream), transient=True)
            self._bar.__enter__()
            self._task = self._bar.add_task("", total=self.total)
        else:
            self._thread = threading.Thread(target=self._heartbeat, daemon=True,
                                            name=f"robotdesc-progress-{self.label}")
            self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=1.0)
        if self._bar is not None:
            self._bar.__exit__(*exc)

    def update(self, done: float, total: float | None = None, detail: str | None = None) -> None:
        """Set the amount done (and the total, and a short note on what runs now)."""
        with self._lock:
            self.done = done
            self.total = total if total is not None else self.total
            self.detail = detail if detail is not None else self.detail
        if self._bar is not None:
            self._bar.update(self._task, completed=done, total=self.total,
                             description=self.detail)

    def note(self, text: str) -> None:
        """Say what starts now: a plain line at once when `stream` is no terminal (as in
        CI), the bar's note on a terminal, nothing when quiet."""
        if self.quiet:
            return
        if self._bar is not None:
            self.update(self.done, detail=text)
            return
        try:
            self.stream.write(f"robotdesc: {self.label}: {text}\n")
            self.stream.flush()
        except (OSError, ValueError):
            pass

    def advance(self, amount: float = 1, detail: str | None = None) -> None:
        """Add `amount` to the amount done."""
        with self._lock:
            done = self.done + amount
        self.update(done, detail=detail)

    def line(self) -> str:
        """The plain progress line: `robotdesc: srdf: 2500 of 10000 samples (25 %), 12 s`."""
        with self._lock:
            done, total, detail = self.done, self.total, self.detail
        unit = f" {self.unit}" if self.unit else ""
        amount = f"{done:g}{unit}" if not total else \
            f"{done:g} of {total:g}{unit} ({100 * done / total:.0f} %)"
        parts = [amount if (done or total) else "working",
                 _duration(time.monotonic() - self._started)]
        return f"robotdesc: {self.label}: " + ", ".join(parts) + (
            f"; {detail}" if detail else "") + "\n"

    def _heartbeat(self) -> None:
        while not self._stop.wait(self.period):
            try:
                self.stream.write(self.line())
                self.stream.flush()
            except (OSError, ValueError):  # stderr closed: stop reporting
                return


def progress_for(ns: Any, label: str, *, total: float | None = None,
                 unit: str = "") -> Progress:
    """The progress of a command run with the parsed arguments `ns` (quiet with -q)."""
    return Progress(label, total=total, unit=unit, quiet=bool(getattr(ns, "quiet", False)))
