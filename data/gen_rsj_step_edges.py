"""Shapiro step edges of the overdamped (RSJ) junction: an independent SciPy reference.

phi' = i + a cos(Omega t) - sin(phi) (time in units of 1 / omega_c).  The
step n spans the biases where the stroboscopic map F(x) = phi(2 pi / Omega;
phi(0) = x) has a fixed point n turns on: its lower edge is the bias where
max_x (F(x) - x) = 2 pi n, its upper edge where min_x (F(x) - x) = 2 pi n.
Written here from the equation alone (pendula is not imported): F by
scipy.integrate.solve_ivp (DOP853, rtol = atol = 1e-12), the extrema of
F(x) - x by 24 samples then scipy.optimize.minimize_scalar (bounded, xatol
1e-10) around the best, the edges by scipy.optimize.brentq (xtol 1e-12) on
the bracket n Omega -+ (a + 1.1) (|phi' - i| <= a + 1).

Cases: two fixed drives and two drawn with numpy's default_rng(45); steps
n = 0, 1, 2.  Stored in data/junction/rsj_step_edges.json.

Run: python data/gen_rsj_step_edges.py   (a few minutes)
"""

import json
import pathlib
import platform
import sys
import time

import numpy as np
import scipy
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, minimize_scalar

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE / "junction" / "rsj_step_edges.json"
SAMPLES = 24


def flow(x, i, a, omega):
    sol = solve_ivp(lambda t, y: i + a * np.cos(omega * t) - np.sin(y), (0.0, 2 * np.pi / omega), [x],
                    method="DOP853", rtol=1e-12, atol=1e-12)
    return sol.y[0, -1]


def gap_extreme(i, a, omega, sign):
    """max (sign = -1) or min (sign = +1) of g(x) = F(x) - x."""
    xs = np.arange(SAMPLES) * 2 * np.pi / SAMPLES
    g = np.array([sign * (flow(x, i, a, omega) - x) for x in xs])
    k = int(np.argmin(g))
    h = 2 * np.pi / SAMPLES
    r = minimize_scalar(lambda x: sign * (flow(x, i, a, omega) - x), bounds=(xs[k] - h, xs[k] + h),
                        method="bounded", options={"xatol": 1e-10})
    return sign * min(r.fun, g[k])


def edges(n, a, omega):
    target = 2 * np.pi * n
    lo, hi = n * omega - (a + 1.1), n * omega + (a + 1.1)
    lower = brentq(lambda i: gap_extreme(i, a, omega, -1) - target, lo, hi, xtol=1e-12)
    upper = brentq(lambda i: gap_extreme(i, a, omega, +1) - target, lo, hi, xtol=1e-12)
    return lower, upper


def main():
    rng = np.random.default_rng(45)
    drives = [(1.0, 1.0), (0.5, 0.3)] + [(float(rng.uniform(0.3, 2.0)), float(rng.uniform(0.4, 2.0)))
                                         for _ in range(2)]
    rows = []
    for a, omega in drives:
        for n in (0, 1, 2):
            t0 = time.time()
            lo, hi = edges(n, a, omega)
            rows.append({"a": a, "omega": omega, "n": n, "lower": lo, "upper": hi,
                         "seconds": round(time.time() - t0, 1)})
            print(rows[-1], flush=True)
    OUT.write_text(json.dumps({
        "what": "reduced bias edges (lower, upper) of the Shapiro step n of phi' = i + a cos(Omega t) - sin(phi), "
                "SciPy DOP853 + minimize_scalar + brentq (gen_rsj_step_edges.py)",
        "generated": time.strftime("%Y-%m-%d"), "scipy": scipy.__version__, "python": sys.version.split()[0],
        "machine": platform.machine(), "rows": rows}, indent=1) + "\n")


if __name__ == "__main__":
    main()
