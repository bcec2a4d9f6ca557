"""What simulate() costs over the kernel's own work, on the exact path and on a spectrum.

Two ratios, each timed side by side in one process, interleaved, best of N (the machine is shared):

* ``simulate(scene, t, method='exact')`` with 11 samples against ``exact_motion`` on the same
  numbers (goal: at most 1.5x);
* ``spectrum`` of 2^20 samples against ``numpy.fft.rfft`` plus numpy's own power and frequencies
  (goal: pendula at least 1.3x faster).

Writes data/bench/simulate_overhead.json (date, machine, load, figures).
Usage:  python data/bench/simulate_overhead.py [--repeats N]
"""

import argparse
import json
import os
import pathlib
import sys
import time

import numpy as np

import platform  # noqa: E402

import pendula  # noqa: E402

OUT = pathlib.Path(__file__).resolve().parent / "simulate_overhead.json"


def best(fns, number, repeats):
    """Best time per call of each function, the rounds interleaved."""
    out = [float("inf")] * len(fns)
    for _ in range(repeats):
        for i, f in enumerate(fns):
            t0 = time.perf_counter()
            for _ in range(number):
                f()
            out[i] = min(out[i], (time.perf_counter() - t0) / number)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=15)
    args = ap.parse_args()
    load = os.getloadavg()
    rec = {"date": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()), "machine": platform.machine(), "cores": os.cpu_count(), "pendula": pendula.__version__,
           "load_average_1_5_15": list(load), "repeats": args.repeats, "clock": "time.perf_counter, best of "
           "interleaved rounds"}
    sc = pendula.Scene(theta0=1.0, v0=0.3)
    t = np.linspace(0.0, 10.0, 11)
    pendula.simulate(sc, t, method="exact")
    a, b = best([lambda: pendula.exact_motion(1.0, 0.3, 1.0, t), lambda: pendula.simulate(sc, t, method="exact")],
                2000, args.repeats)
    rec["exact"] = {"samples": 11, "exact_motion_us": a * 1e6, "simulate_exact_us": b * 1e6, "ratio": b / a,
                    "goal": "ratio <= 1.5"}
    print(f"exact_motion {a * 1e6:.2f} us, simulate(method='exact') {b * 1e6:.2f} us: {b / a:.2f}x")
    # the first call with these knobs on a scene (the kernel checks the changed fields), and the old way:
    # a new Scene built and checked by Scene.replace, then run
    fresh = [pendula.Scene(theta0=1.0, v0=0.3) for _ in range(2000 * args.repeats)]
    it = iter(fresh)
    c, d = best([lambda: pendula.simulate(next(it), t, method="exact"),
                 lambda: pendula.simulate(sc.replace(method="exact"), t)], 1000, args.repeats)
    rec["exact"].update({"simulate_exact_first_call_us": c * 1e6, "first_call_ratio": c / a,
                         "replace_then_simulate_us": d * 1e6, "replace_then_simulate_ratio": d / a})
    print(f"first call on a fresh scene {c * 1e6:.2f} us ({c / a:.2f}x); Scene.replace then simulate "
          f"{d * 1e6:.2f} us ({d / a:.2f}x)")
    spectrum_figures(rec, args.repeats)
    OUT.write_text(json.dumps(rec, indent=1) + "\n")
    print(f"wrote {OUT}")


def spectrum_figures(rec, repeats):
    n = 1 << 20
    rng = np.random.default_rng(20261203)
    x = rng.standard_normal(n)
    dt = 0.01
    t = np.arange(n) * dt

    def numpy_way():
        c = np.fft.rfft(x)
        p = (c.real ** 2 + c.imag ** 2) * (2.0 / n ** 2)
        f = np.fft.rfftfreq(n, dt) * (2.0 * np.pi)      # angular frequency, as pendula's
        return f, p

    pendula.spectrum(t, x)
    a, b = best([numpy_way, lambda: pendula.spectrum(t, x)], 3, max(5, repeats // 2))
    rec["spectrum"] = {"samples": n, "numpy_rfft_power_freq_ms": a * 1e3, "pendula_spectrum_ms": b * 1e3,
                       "speedup": a / b, "goal": "speedup >= 1.3"}
    print(f"numpy rfft + power + rfftfreq {a * 1e3:.2f} ms, pendula.spectrum {b * 1e3:.2f} ms: {a / b:.2f}x")


if __name__ == "__main__":
    main()
