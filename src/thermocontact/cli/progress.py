"""Progress of the commands on standard error, once a command has run 2 s."""

from __future__ import annotations

import click

__all__ = ["RefinementProgress", "StageProgress"]


class RefinementProgress:
    """Refinement progress on standard error, a line per level once a solve has run 2 s."""

    AFTER = 2.0
    #: A level this large takes seconds by itself: announced at once.
    LARGE_N = 512

    def __init__(self):
        import time

        self._clock = time.perf_counter
        self._start = self._clock()

    def __call__(self, n, estimate):
        elapsed = self._clock() - self._start
        if elapsed < self.AFTER and n < self.LARGE_N:
            return
        est = "" if estimate is None else f", error estimate so far {estimate:.1e}"
        click.echo(f"solving at n = {n}{est} ({elapsed:.0f} s elapsed)", err=True)



class StageProgress:
    """``progress(stage, done, total)``: one :class:`ProgressLine` per stage, shown
    once the command has run 2 s."""

    def __init__(self, label):
        import time

        self.label, self.start, self.line, self.stage = label, time.monotonic(), None, None

    def __call__(self, stage, done, total):
        import time

        from ..execution.progress import ProgressLine

        if stage != self.stage:
            self.close()
            delay = max(0.0, 2.0 - (time.monotonic() - self.start))
            self.stage, self.line = stage, ProgressLine(f"{self.label}: {stage}", "steps",
                                                         delay=delay)
        self.line(done, total)

    def close(self):
        if self.line is not None:
            self.line.close()
