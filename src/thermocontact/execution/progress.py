"""One line of progress for long runs: done, total, rate and time left."""

from __future__ import annotations

import sys
import time

__all__ = ["ProgressLine"]


def _clock(seconds: float) -> str:
    seconds = int(round(seconds))
    h, rest = divmod(seconds, 3600)
    m, s = divmod(rest, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m}:{s:02d}"


class ProgressLine:
    """``progress(done, total)``: a line on ``stream``, rewritten in place.

    Silent for the first ``delay`` seconds (a short run shows nothing) and at most
    every ``interval`` seconds after.  Rates count from the first report, so that
    work resumed from disk does not inflate them.

    Parameters
    ----------
    label : str
    unit : str
        What is counted, e.g. ``"points"``.
    stream : file, optional
        Default: standard error.
    delay, interval : float
        Seconds.
    """

    def __init__(self, label: str, unit: str = "tasks", stream=None, delay=2.0, interval=0.5):
        self.label, self.unit = label, unit
        self.stream = sys.stderr if stream is None else stream
        self.delay, self.interval = delay, interval
        self._start = time.monotonic()
        self._first = None
        self._last = -float("inf")
        self._shown = False

    def text(self, done: int, total: int, now: float | None = None) -> str:
        """The line for ``done`` of ``total``."""
        now = time.monotonic() if now is None else now
        if self._first is None:
            self._first = (now, done)
        t0, d0 = self._first
        rate = (done - d0) / (now - t0) if now > t0 and done > d0 else 0.0
        pct = 100.0 * done / total if total else 100.0
        line = f"{self.label}: {done}/{total} {self.unit} ({pct:.0f}%)"
        if rate > 0.0:
            line += f", {rate:.3g} {self.unit}/s, {_clock((total - done) / rate)} left"
        return line

    def __call__(self, done: int, total: int):
        now = time.monotonic()
        line = self.text(done, total, now)
        tty = getattr(self.stream, "isatty", lambda: False)()
        # Rewritten in place on a terminal; a line every ten seconds in a log.
        interval = self.interval if tty else max(self.interval, 10.0)
        if now - self._start < self.delay or (now - self._last < interval and done < total):
            return
        self._last = now
        if tty:
            self._shown = True
            self.stream.write("\r" + line + "\033[K")
        else:
            self.stream.write(line + "\n")
        self.stream.flush()

    def close(self):
        """End the line (if one was shown)."""
        if self._shown:
            self.stream.write("\n")
            self.stream.flush()
            self._shown = False
