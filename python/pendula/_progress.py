"""Progress on long work, by tqdm (pendula's one progress library).

Library calls keep it off unless asked (``progress=True``); the command line
turns it on.  Work shorter than two seconds draws nothing; tqdm redraws one
line on a terminal and writes plain lines elsewhere; ``note`` shows what is
being done.  Every bar of pendula is this one (the sweeps' too).  Without tqdm
(it comes with the ``sweep`` extra) a bar counts and draws nothing: progress
is never a reason for a run to fail.
"""

from __future__ import annotations

import sys


class Progress:
    """A tqdm bar over ``total`` steps, or nothing when ``enabled`` is False.

    Parameters
    ----------
    total : int
        Steps of the work.
    label : str
        What the work is (the bar's description).
    stream : file, optional
        Where to draw (default standard error).
    enabled : bool, optional
        False: a bar that counts but draws nothing (so is a bar without tqdm installed).
    initial : int, optional
        Steps already done (a resumed sweep).
    unit : str, optional
        What a step is (tqdm's unit: 'it', 'chunk').
    """

    def __init__(self, total: int, label: str, stream=None, enabled: bool = True, initial: int = 0,
                 unit: str = "it"):
        self.total = max(int(total), 1)
        self.done = min(self.total, max(int(initial), 0))
        self._bar = None
        if enabled:
            try:
                from tqdm.auto import tqdm
            except ImportError:      # tqdm not installed: count, draw nothing
                return
            self._bar = tqdm(total=self.total, initial=self.done, desc=label, file=stream or sys.stderr,
                             leave=True, mininterval=0.5, dynamic_ncols=True, delay=2.0, unit=unit)

    def update(self, n: int = 1, note: str = "") -> None:
        """Count n steps done; note says what the last one was."""
        self.done = min(self.total, self.done + n)
        if self._bar is not None:
            if note:
                self._bar.set_postfix_str(note[:40], refresh=False)
            self._bar.update(n)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False
