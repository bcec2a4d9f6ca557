"""A small progress bar on standard error (no dependency).

On a terminal it redraws one line; elsewhere (CI logs) work that runs longer
than two seconds prints a line at every 10 %, so long work shows it is moving.
"""

from __future__ import annotations

import sys
import time


class Progress:
    def __init__(self, total: int, label: str, stream=None, enabled: bool = True):
        self.total = max(int(total), 1)
        self.label = label
        self.stream = stream or sys.stderr
        self.enabled = enabled
        self.done = 0
        self.t0 = time.perf_counter()
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self._last_decile = -1

    def update(self, n: int = 1, note: str = "") -> None:
        self.done = min(self.total, self.done + n)
        if not self.enabled:
            return
        frac = self.done / self.total
        el = time.perf_counter() - self.t0
        if self.tty:
            width = 30
            bar = "#" * int(frac * width) + "-" * (width - int(frac * width))
            self.stream.write(f"\r{self.label} [{bar}] {self.done}/{self.total} {el:6.1f}s {note[:40]:40s}")
            if self.done == self.total:
                self.stream.write("\n")
            self.stream.flush()
        else:
            decile = int(frac * 10)
            if el < 2.0 and self._last_decile < 0:
                return  # short work stays quiet in logs
            if decile != self._last_decile or self.done == self.total:
                self._last_decile = decile
                self.stream.write(f"{self.label}: {self.done}/{self.total} ({100 * frac:3.0f} %) {el:.1f}s {note}\n")
                self.stream.flush()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False
