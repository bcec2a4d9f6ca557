"""Independent reference for the lyapunov measure (tests/test_sweep_lyapunov.py).

The driven damped pendulum theta'' = -sin(theta) - beta theta' + A cos(Omega t)
(beta = 0.5, Omega = 2/3, eps = 1, from rest), its tangent equations for two
vectors, integrated by scipy's solve_ivp (DOP853, rtol 1e-11, atol 1e-13) --
not pendula's integrator -- with Gram-Schmidt once per drive period T (pendula
renormalises every T/6: a different schedule, the same exponents), after a
transient of N_TR periods, averaged over N_AVG periods; the error is the
standard error of the mean over 8 blocks (as pendula's).  Amplitudes: the two
chaotic ones of the brief (1.15, 1.5) and random ones (uniform in 0.9 .. 1.5,
seeded).  Writes lyapunov_reference.json beside this file.

Run once (about 40 s of CPU per amplitude, `nice` it):
    nice .venv/bin/python data/lyapunov/gen_reference.py
"""

import json
import math
import pathlib
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

BETA, OMEGA, EPS = 0.5, 2.0 / 3.0, 1.0
N_TR, N_AVG, NBLOCK = 200, 4000, 8
RTOL, ATOL = 1e-11, 1e-13


def exponents(amp):
    T = 2 * math.pi / OMEGA

    def f(t, y):
        th, v, x1, y1, x2, y2 = y
        c = -EPS * math.cos(th)
        return [v, -EPS * math.sin(th) - BETA * v + amp * math.cos(OMEGA * t),
                y1, c * x1 - BETA * y1, y2, c * x2 - BETA * y2]

    y = np.array([0.0, 0.0, 1.0, 0.0, 0.0, 1.0])
    s1 = np.zeros(N_AVG)
    s2 = np.zeros(N_AVG)
    for k in range(N_TR + N_AVG):
        # the clock restarts at 0 each period (the drive is T-periodic)
        sol = solve_ivp(f, (0.0, T), y, method="DOP853", rtol=RTOL, atol=ATOL)
        y = sol.y[:, -1].copy()
        y[0] = math.remainder(y[0], 2 * math.pi)
        w1, w2 = y[2:4], y[4:6]
        n1 = math.hypot(*w1)
        w1 = w1 / n1
        w2 = w2 - (w2 @ w1) * w1
        n2 = math.hypot(*w2)
        w2 = w2 / n2
        y[2:4], y[4:6] = w1, w2
        if k >= N_TR:
            s1[k - N_TR] = math.log(n1)
            s2[k - N_TR] = math.log(n2)
    lam1 = s1.sum() / (N_AVG * T)
    lam2 = s2.sum() / (N_AVG * T)
    blocks = [b.sum() / (b.size * T) for b in np.array_split(s1, NBLOCK)]
    err = float(np.std(blocks, ddof=1) / math.sqrt(NBLOCK))
    return lam1, lam2, err


def main():
    rng = np.random.default_rng(20261123)
    amps = [1.15, 1.5] + [float(a) for a in rng.uniform(0.9, 1.5, 3)]
    rows = []
    for a in amps:
        t0 = time.process_time()
        l1, l2, e = exponents(a)
        rows.append({"amp": a, "lambda1": l1, "lambda2": l2, "err": e})
        print(f"A = {a:.6f}: lambda1 = {l1:.6f} +- {e:.1e}, lambda2 = {l2:.6f}, sum + beta = {l1 + l2 + BETA:.1e}"
              f" ({time.process_time() - t0:.0f} s)", file=sys.stderr)
    out = {"what": __doc__.split("\n\n")[1], "beta": BETA, "omega": OMEGA, "eps": EPS, "theta0": 0.0, "v0": 0.0,
           "n_transient_periods": N_TR, "n_average_periods": N_AVG, "rtol": RTOL, "atol": ATOL, "points": rows}
    p = pathlib.Path(__file__).with_name("lyapunov_reference.json")
    p.write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
