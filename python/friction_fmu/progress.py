"""Progress on stderr: finished/total, failures, elapsed time and ETA.

On a terminal, one bar redrawn in place. Anywhere else (a log file, a pipe, a CI job) plain
lines, at most one every `every` seconds plus the last: a log gets no carriage returns and no
thousand lines of a redrawn bar."""
import math
import sys
import time


class Progress:
    def __init__(self, total, stream=None, enabled=True, width=30, every=5.0):
        self.total, self.done, self.failed = total, 0, 0
        self.stream = stream or sys.stderr
        self.enabled = enabled
        self.live = self.stream.isatty()
        self.width = width
        self.every = 0.2 if self.live else every  # a bar is redrawn five times a second
        self.began = time.monotonic()
        self._shown = self.began
        if self.live:
            self._draw(force=True)

    def advance(self, failed=False):
        self.done += 1
        self.failed += int(failed)
        self._draw(force=self.done == self.total)

    def close(self):
        if self.enabled and self.live:
            self.stream.write("\n")
            self.stream.flush()

    def _draw(self, force=False):
        now = time.monotonic()
        if not self.enabled or (not force and now - self._shown < self.every):
            return
        self._shown = now
        elapsed = now - self.began
        eta = elapsed / self.done * (self.total - self.done) if self.done else float("nan")
        failed = f", {self.failed} failed" if self.failed else ""
        counts = f"{self.done}/{self.total}{failed}  elapsed {_clock(elapsed)}  ETA {_clock(eta)}"
        if self.live:
            filled = self.width * self.done // max(self.total, 1)
            self.stream.write(f"\r[{'#' * filled}{'.' * (self.width - filled)}] {counts} ")
        else:
            self.stream.write(f"{counts}\n")
        self.stream.flush()


def _clock(seconds):
    if math.isnan(seconds):  # no estimate before the first point finishes
        return "--:--"
    minutes, secs = divmod(round(seconds), 60)
    return f"{minutes:02d}:{secs:02d}"
