"""Long kernel calls that Ctrl-C can stop, and that let other threads run.

The binding releases the GIL during its long calls (``!f2py threadsafe``),
but a signal reaches Python only when the main thread runs Python code.  So a
long call runs in a worker thread while the main thread waits in short
joins; on Ctrl-C the main thread sets the call's cancel flag (a one-element
int32 array the kernel polls every few thousand steps), waits for the
kernel to notice, and raises KeyboardInterrupt.  Short calls (and calls from
threads other than the main one, which never see signals) run directly.
"""

from __future__ import annotations

import threading

import numpy as np

__all__ = ["cancel_flag", "call"]


def cancel_flag() -> np.ndarray:
    """A fresh cancel flag for one kernel call."""
    return np.zeros(1, dtype=np.int32)


def call(fn, *args, cancel: np.ndarray, long: bool = True):
    """fn(*args) with ``cancel`` among the args; interruptible when ``long``."""
    if not long or threading.current_thread() is not threading.main_thread():
        return fn(*args)
    box: dict = {}

    def target():
        try:
            box["result"] = fn(*args)
        except BaseException as exc:  # noqa: BLE001 - handed to the caller below
            box["error"] = exc

    worker = threading.Thread(target=target, name="pendula-kernel", daemon=True)
    worker.start()
    try:
        while worker.is_alive():
            worker.join(0.05)
    except BaseException:      # Ctrl-C, or SystemExit from a SIGTERM handler
        cancel[0] = 1
        worker.join()
        raise
    if "error" in box:
        raise box["error"]
    return box["result"]
