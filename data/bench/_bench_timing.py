"""What the cost scripts beside this file share: one timer and the loader of a
reference script from data/ (the peer a cost script times pendula against).

Imported as ``from _bench_timing import ...``: each script runs as
``python data/bench/NAME.py``, so this folder is first on sys.path.
"""
import argparse
import importlib.util
import sys
import time
from pathlib import Path

DATA = Path(__file__).resolve().parent.parent


def timed(fn):
    """Run ``fn()`` once: (wall seconds, CPU seconds of this process, its result)."""
    t0, c0 = time.perf_counter(), time.process_time()
    out = fn()
    return time.perf_counter() - t0, time.process_time() - c0, out


def reference_script(filename, name):
    """Import data/FILENAME as a module called NAME (data/ on sys.path, for its own helpers)."""
    if str(DATA) not in sys.path:
        sys.path.insert(0, str(DATA))
    spec = importlib.util.spec_from_file_location(name, DATA / filename)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def cost_arguments(doc, n, n_help, threads_help="OpenMP threads"):
    """The options every cost script takes: --n (its size), --repeat (interleaved
    repetitions, best of) and --threads.  The script adds its own and parses."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("--n", type=int, default=n, help=n_help)
    ap.add_argument("--repeat", type=int, default=3, help="interleaved repetitions (best of)")
    ap.add_argument("--threads", type=int, default=2, help=threads_help)
    return ap
