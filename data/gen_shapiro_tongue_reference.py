"""Reference edges of the Shapiro steps n = 1, 2 of the driven pendulum (a junction), with scipy.

    theta'' = -beta theta' - sin(theta) + A cos(omega t) + tau,    beta = 1, omega = 2

Independent of pendula (the equation, flows and Newton from gen_bifurcation_curve_reference.py):
the locked orbit of step n is a fixed point of the stroboscopic map advancing n turns.  Every phase
theta of the section is such a fixed point at some torque (Newton in (v, tau) at fixed theta), and
the step's edges are the extremes of that torque over theta: det(M - I) = 0.  The phases are scanned
in 96 steps around the circle, the two sign changes of det(M - I) bracketed, and each solved by
brentq (xtol 1e-14) in theta.

Run: python data/gen_shapiro_tongue_reference.py   (a few minutes)
Output: data/shapiro_tongue_reference.json.
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

from gen_bifurcation_curve_reference import branch_at_theta

BETA, OMEGA = 1.0, 2.0


def edges(n, A, tau0):
    """The lower and upper torque of step n at rf amplitude A."""
    state = {"v": n * OMEGA, "tau": tau0}

    def solve(theta):
        v, tau, M = branch_at_theta(theta, state["v"], state["tau"], OMEGA, BETA, A, "tau", winding=n)
        state["v"], state["tau"] = v, tau
        return tau, np.linalg.det(M - np.eye(2))
    rows = []
    for th in np.linspace(-math.pi, math.pi, 97):
        tau, g = solve(th)
        rows.append((th, tau, g, state["v"]))
    out = []
    for (ta, tau_a, ga, va), (tb, _, gb, _) in zip(rows[:-1], rows[1:]):
        if ga * gb < 0:
            state["v"], state["tau"] = va, tau_a
            th = brentq(lambda x: solve(x)[1], ta, tb, xtol=1e-14, rtol=4 * np.finfo(float).eps, maxiter=200)
            tau, _ = solve(th)
            out.append((tau, th, state["v"]))
    assert len(out) == 2, (n, A, out)
    out.sort()
    return out


def main():
    t0 = time.time()
    res = {"beta": BETA, "omega": OMEGA, "rtol": 1e-12, "edges": []}
    for n in (1, 2):
        for A in (0.5, 1.5, 2.0):
            (lo, thl, vl), (hi, thh, vh) = edges(n, A, BETA * n * OMEGA)
            res["edges"].append({"n": n, "A": A, "lower": lo, "upper": hi, "theta_lower": thl, "v_lower": vl,
                                 "theta_upper": thh, "v_upper": vh})
            print(n, A, lo, hi, f"{time.time() - t0:.0f} s")
    Path(__file__).with_name("shapiro_tongue_reference.json").write_text(json.dumps(res, indent=1))


if __name__ == "__main__":
    main()
