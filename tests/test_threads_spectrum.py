"""Spectra from several threads at once.

Before plans were counted while in use, one thread could free a cached FFTW
plan (evicting it for a new length) between another thread's look-up and its
execution: a segfault in most runs.  Here threads hammer spectrum/spectra on
more lengths than the plan cache holds, with a tiny switch interval, and every
result must equal the serial one bit for bit (the kernel call releases the GIL,
`!f2py threadsafe`, and must not change a single bit).
"""

import importlib

import numpy as np

import pendula
from conftest import run_threads

spectrum_module = importlib.import_module("pendula.spectrum")


def _work(seed, calls):
    rng = np.random.default_rng(seed)
    jobs = []
    for _ in range(calls):
        n = int(rng.integers(4, 4 + 2 * spectrum_module._MAX_PLANS + 8))   # more lengths than the cache
        m = int(rng.integers(0, 3))
        window = [None, "hann"][int(rng.integers(0, 2))]
        t = np.arange(n) * float(rng.uniform(0.01, 1.0))
        x = rng.standard_normal((m, n)) if m else rng.standard_normal(n)
        jobs.append((t, x, window))
    return jobs


def _run(jobs):
    out = []
    for t, x, window in jobs:
        if x.ndim == 1:
            out.append([pendula.spectrum(t, x, window=window).power])
        else:
            out.append([s.power for s in pendula.spectra(t, x, window=window)])
    return out


def test_threads_hammering_spectra_of_many_lengths_match_serial_results():
    nthreads, calls = 4, 1500
    jobs = [_work(1000 + i, calls) for i in range(nthreads)]
    serial = [_run(j) for j in jobs]
    results = [None] * nthreads
    def worker(i):
        def go():
            results[i] = _run(jobs[i])
        return go

    errors = run_threads([worker(i) for i in range(nthreads)])
    assert not errors, errors
    for got, want in zip(results, serial):
        assert len(got) == len(want) == calls
        for g, w in zip(got, want):
            assert len(g) == len(w)
            for a, b in zip(g, w):
                assert np.array_equal(a, b)


def test_one_long_length_and_a_cycle_of_others_in_two_threads():
    # a case a fuzz found: length 64 in one thread, 65..81 in another
    t64 = np.arange(64) * 0.1
    want64 = pendula.spectrum(t64, np.sin(t64)).power
    others = {n: pendula.spectrum(np.arange(n) * 0.1, np.sin(np.arange(n) * 0.1)).power
              for n in range(65, 82)}
    bad = []

    def a():
        for _ in range(3000):
            if not np.array_equal(pendula.spectrum(t64, np.sin(t64)).power, want64):
                bad.append(64)

    def b():
        for i in range(3000):
            n = 65 + i % 17
            t = np.arange(n) * 0.1
            if not np.array_equal(pendula.spectrum(t, np.sin(t)).power, others[n]):
                bad.append(n)

    assert run_threads([a, b]) == []
    assert bad == []
    assert len(spectrum_module._PLANS) <= spectrum_module._MAX_PLANS
