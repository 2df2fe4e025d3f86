"""A one-line progress bar on stderr: finished/total, failures, elapsed time and ETA."""
import math
import sys
import time


class Progress:
    def __init__(self, total, stream=None, enabled=True, width=30):
        self.total, self.done, self.failed = total, 0, 0
        self.stream = stream or sys.stderr
        self.enabled = enabled
        self.width = width
        self.began = time.monotonic()
        self._shown = 0.0
        self._draw(force=True)

    def advance(self, failed=False):
        self.done += 1
        self.failed += int(failed)
        self._draw(force=self.done == self.total)

    def close(self):
        if self.enabled:
            self.stream.write("\n")
            self.stream.flush()

    def _draw(self, force=False):
        now = time.monotonic()
        if not self.enabled or (not force and now - self._shown < 0.2):
            return
        self._shown = now
        elapsed = now - self.began
        filled = self.width * self.done // max(self.total, 1)
        eta = elapsed / self.done * (self.total - self.done) if self.done else float("nan")
        failed = f", {self.failed} failed" if self.failed else ""
        self.stream.write(
            f"\r[{'#' * filled}{'.' * (self.width - filled)}] {self.done}/{self.total}{failed}"
            f"  elapsed {_clock(elapsed)}  ETA {_clock(eta)} ")
        self.stream.flush()


def _clock(seconds):
    if math.isnan(seconds):  # no estimate before the first point finishes
        return "--:--"
    minutes, secs = divmod(round(seconds), 60)
    return f"{minutes:02d}:{secs:02d}"
