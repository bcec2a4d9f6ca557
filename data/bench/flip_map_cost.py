"""The cost of a flip-time map: pendula against SciPy on the same pixels, in one run.

A benchmark, not a test (no time is asserted).  npix seeded random starts from
rest that the energy allows to flip, equal point masses and lengths, searched
up to t_max = 30: pendula's DoublePendulum.flip_map (one thread, each pixel
at rtol and at rtol / 10, as the map does) against SciPy's solve_ivp (DOP853,
terminal events abs(theta_i) = pi, a NumPy-free right-hand side) doing the
same two runs per pixel.  Prints seconds per pixel, the ratio, and how far
the two codes' flip times differ (the accuracy they share).

Run: python data/bench/flip_map_cost.py [npix]
"""

import math
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

import pendula


def scipy_flip(th1, th2, t_max, rtol):
    def rhs(t, y):
        t1, t2, w1, w2 = y
        d = t1 - t2
        c, s = math.cos(d), math.sin(d)
        r1 = -s * w2 * w2 - 2.0 * math.sin(t1)
        r2 = s * w1 * w1 - math.sin(t2)
        det = 2.0 - c * c                       # M = [[2, c], [c, 1]]
        return [w1, w2, (r1 - c * r2) / det, (2.0 * r2 - c * r1) / det]

    evs = []
    for j in (0, 1):
        def ev(t, y, j=j):
            return abs(y[j]) - math.pi
        ev.terminal = True
        evs.append(ev)
    sol = solve_ivp(rhs, (0.0, t_max), [th1, th2, 0.0, 0.0], method="DOP853", rtol=rtol, atol=rtol, events=evs)
    hits = [te[0] for te in sol.t_events if te.size]
    return min(hits) if hits else math.inf


def main(npix: int = 40, t_max: float = 30.0, rtol: float = 1e-10) -> None:
    rng = np.random.default_rng(11)
    pts = []
    while len(pts) < npix:
        a, b = rng.uniform(-math.pi, math.pi, 2)
        if not pendula.flip_forbidden(a, b):
            pts.append((a, b))
    pts = np.array(pts)
    dp = pendula.DoublePendulum()
    t0 = time.perf_counter()
    tp = np.array([dp.flip_map([a], [b], t_max=t_max, rtol=rtol, atol=rtol, threads=1).time[0, 0] for a, b in pts])
    t_pendula = time.perf_counter() - t0
    t0 = time.perf_counter()
    ts = np.array([scipy_flip(a, b, t_max, rtol) for a, b in pts])
    for a, b in pts:
        scipy_flip(a, b, t_max, rtol / 10)
    t_scipy = time.perf_counter() - t0
    both = np.isfinite(tp) & np.isfinite(ts)
    rel = np.abs(tp[both] - ts[both]) / ts[both]
    print(f"{npix} pixels, t_max = {t_max:g}, rtol = {rtol:g} (each pixel twice: rtol and rtol/10)")
    print(f"pendula  {t_pendula / npix * 1e3:9.2f} ms per pixel")
    print(f"scipy    {t_scipy / npix * 1e3:9.2f} ms per pixel   ratio scipy / pendula = {t_scipy / t_pendula:.1f}")
    print(f"flip times: {int(both.sum())} both finite, median relative difference {np.median(rel):.1e}, "
          f"{int(np.sum(rel > 1e-3))} differ by more than 1e-3 (chaotic pixels), "
          f"{int(np.sum(np.isfinite(tp) != np.isfinite(ts)))} flip in one code only")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 40)
