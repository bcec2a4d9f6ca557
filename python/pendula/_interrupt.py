"""Long kernel calls that Ctrl-C can stop, and that let other threads run.

The binding releases the GIL during its long calls (``!f2py threadsafe``),
but a signal reaches Python only when the main thread runs Python code.  So a
long call runs in a worker thread while the main thread waits in short
joins; on Ctrl-C the main thread sets the call's cancel flag (a one-element
int32 array the kernel polls every few thousand steps), waits for the
kernel to notice, and raises KeyboardInterrupt.  Short calls (and calls from
threads other than the main one, which never see signals) run directly --
unless the thread watches a stop condition (:func:`watching`: a task of a
sweep on a Dask worker polls the sweep's stop Event), which is then polled
twice a second while the kernel runs, and stops it (:class:`Cancelled`).
"""

from __future__ import annotations

import contextlib
import threading
import time

import numpy as np

__all__ = ["cancel_flag", "call", "watching", "Cancelled"]

_local = threading.local()


class Cancelled(Exception):
    """A kernel call stopped because the condition its thread watches (:func:`watching`) came true."""


@contextlib.contextmanager
def watching(stop):
    """Within the block, long kernel calls of this thread poll ``stop()`` twice a second
    and are cancelled (:class:`Cancelled`) when it answers True."""
    before = getattr(_local, "stop", None)
    _local.stop = stop
    try:
        yield
    finally:
        _local.stop = before


def cancel_flag() -> np.ndarray:
    """A fresh cancel flag for one kernel call."""
    return np.zeros(1, dtype=np.int32)


def call(fn, *args, cancel: np.ndarray, long: bool = True):
    """fn(*args) with ``cancel`` among the args; interruptible when ``long``."""
    stop = getattr(_local, "stop", None)
    if not long or (stop is None and threading.current_thread() is not threading.main_thread()):
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
        poll = time.monotonic() + 0.5
        while worker.is_alive():
            worker.join(0.05)
            if stop is not None and time.monotonic() >= poll:
                poll = time.monotonic() + 0.5
                if stop():
                    raise Cancelled("stopped: the work this call belongs to was cancelled")
    except BaseException:      # Ctrl-C, or SystemExit from a SIGTERM handler, or Cancelled
        cancel[0] = 1
        worker.join()
        raise
    if "error" in box:
        raise box["error"]
    return box["result"]
