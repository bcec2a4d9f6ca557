"""Reference bifurcation points of the damped driven pendulum, from the equation alone with scipy.

    theta'' = -beta theta' - sin(theta) + A cos(omega t) + tau

Written independently of pendula (no import of it): scipy's DOP853 at rtol = atol = 1e-13 on the
equation and its variational equations, Newton's method on the stroboscopic map, brentq on the test
function of the Floquet multipliers (xtol 1e-14), and bisection on whether the saddle's unstable
manifold passes the next saddle.  Output: data/continuation_reference.json.

1. The route of the attracting orbit from A = 1.0 (beta = 0.5, omega = 2/3, tau = 0): the
   symmetry-breaking pitchfork of the symmetric period-1 orbit (its monodromy over the full period
   has the eigenvalue +1; the symmetric orbit is found as a fixed point of the half-period map
   G(x) = -phi_{T/2}(x), where Newton stays well conditioned through the pitchfork), then the first
   period doublings of the asymmetric orbit and its children (1 + tr M + det M = 0, the eigenvalue -1).
   Each child is reached by simulating past the doubling from the parent orbit and Newton on the
   2k-fold map.
2. The retrapping (homoclinic) torque of the undriven pendulum at four dampings: the torque where
   the unstable manifold of the saddle at pi - asin(tau) stops passing the next saddle (bisection on
   the outcome of integrating it with events: over the next saddle, or v = 0 first).

Run: python data/gen_continuation_reference.py   (about two minutes)
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

BETA, OMEGA = 0.5, 2.0 / 3.0
TD = 2 * math.pi / OMEGA
RTOL = ATOL = 1e-13


def rhs(t, y, A, beta=BETA, tau=0.0):
    th, v, a, b, c, d = y
    dth = -math.cos(th)
    return [v, -beta * v - math.sin(th) + A * math.cos(OMEGA * t) + tau,
            b, dth * a - beta * b, d, dth * c - beta * d]


def flow(x, T, A):
    """The state and the monodromy after time T from x at t = 0."""
    s = solve_ivp(rhs, (0.0, T), [x[0], x[1], 1.0, 0.0, 0.0, 1.0], method="DOP853", rtol=RTOL, atol=ATOL,
                  args=(A,))
    y = s.y[:, -1]
    return y[:2], np.array([[y[2], y[4]], [y[3], y[5]]])


def newton(F, x, it=30):
    for _ in range(it):
        r, J = F(x)
        dx = np.linalg.solve(J, -r)
        x = x + dx
        if np.max(np.abs(dx)) < 1e-12:
            return x
    raise RuntimeError("Newton did not converge")


def orbit(x, A, k):
    """A period-k orbit of the stroboscopic map (no winding) near x."""
    def F(x):
        y, M = flow(x, k * TD, A)
        return y - x, M - np.eye(2)
    return newton(F, x)


def symmetric_orbit(x, A):
    """A fixed point of G(x) = -phi_{T/2}(x) (with theta taken modulo 2 pi by m)."""
    y, _ = flow(x, TD / 2, A)
    m = round((y[0] + x[0]) / (2 * math.pi))

    def F(x):
        y, M = flow(x, TD / 2, A)
        return np.array([2 * math.pi * m - y[0] - x[0], -y[1] - x[1]]), -M - np.eye(2)
    return newton(F, x)


def settle(x, A, periods):
    """The state after some drive periods (transients)."""
    s = solve_ivp(lambda t, y: rhs(t, list(y) + [1, 0, 0, 1], A)[:2], (0.0, periods * TD), x, method="DOP853",
                  rtol=1e-10, atol=1e-10)
    th, v = s.y[:, -1]
    return np.array([math.remainder(th, 2 * math.pi), v])


def cascade():
    out = []
    # the symmetric period-1 attractor at A = 1.0
    x = symmetric_orbit(settle(np.array([0.1, 1.9]), 1.0, 200), 1.0)
    cache = {1.0: x}

    def psi_pitch(A):
        near = min(cache, key=lambda a: abs(a - A))
        xs = symmetric_orbit(cache[near], A)
        cache[A] = xs
        _, M = flow(xs, TD, A)            # the full-period monodromy of the symmetric orbit
        return 1 - np.trace(M) + np.linalg.det(M)
    a_pf = brentq(psi_pitch, 1.0, 1.01, xtol=1e-14, rtol=1e-15)
    xs = cache[min(cache, key=lambda a: abs(a - a_pf))]
    out.append({"kind": "pitchfork", "k": 1, "value": a_pf, "theta": float(xs[0]), "v": float(xs[1])})
    print(f"pitchfork {a_pf!r}")
    # the asymmetric child: past the pitchfork, from the symmetric orbit pushed off
    A_lo = a_pf + 0.01
    x = orbit(settle(xs + np.array([0.05, 0.0]), A_lo, 300), A_lo, 1)
    k, prev = 1, a_pf
    for level in range(4):
        cache = {A_lo: x}

        def psi_pd(A, k=k, cache=cache):
            near = min(cache, key=lambda a: abs(a - A))
            xo = orbit(cache[near], A, k)
            cache[A] = xo
            _, M = flow(xo, k * TD, A)
            return 1 + np.trace(M) + np.linalg.det(M)
        # bracket: step A up from A_lo until the test function changes sign
        A_hi, step = A_lo, (0.004 if k == 1 else (prev_gap / 4.0 / 8))
        while psi_pd(A_hi) > 0:
            A_lo_b = A_hi
            A_hi += step
        a_pd = brentq(psi_pd, A_lo_b, A_hi, xtol=1e-14, rtol=1e-15)
        xo = cache[min(cache, key=lambda a: abs(a - a_pd))]
        out.append({"kind": "period-doubling", "k": k, "value": a_pd, "theta": float(xo[0]), "v": float(xo[1])})
        print(f"period-doubling k={k} {a_pd!r}")
        prev_gap = a_pd - prev
        prev = a_pd
        if level == 3:
            break
        # the period-2k child, past the doubling
        A_lo = a_pd + prev_gap / 4.669 / 4
        y = settle(xo + np.array([1e-3, 0.0]), A_lo, 400 * k)
        x = orbit(y, A_lo, 2 * k)
        yk, _ = flow(x, k * TD, A_lo)
        assert np.max(np.abs(yk - x)) > 1e-5, "the child is not of period 2k"
        k *= 2
    return out


def retrapping(beta):
    """The torque at which the unstable manifold of the saddle just reaches the next saddle."""
    def passes(tau):
        ths = math.pi - math.asin(tau)
        J = np.array([[0.0, 1.0], [-math.cos(ths), -beta]])
        lam, vec = np.linalg.eig(J)
        i = int(np.argmax(lam.real))
        e = np.real(vec[:, i])
        e = e / e[0]
        d = 1e-9
        y0 = [ths + d, d * e[1]]

        def over(t, y):
            return y[0] - (ths + 2 * math.pi)
        over.terminal, over.direction = True, 1

        def back(t, y):
            return y[1]
        back.terminal, back.direction = True, -1
        s = solve_ivp(lambda t, y: [y[1], -beta * y[1] - math.sin(y[0]) + tau], (0.0, 5000.0), y0,
                      method="DOP853", rtol=RTOL, atol=1e-15, events=(over, back))
        if len(s.t_events[0]):
            return True
        if len(s.t_events[1]):
            return False
        raise RuntimeError("neither event")
    lo, hi = 1e-3, 0.99
    assert passes(hi) and not passes(lo)
    while hi - lo > 2e-15:
        mid = 0.5 * (lo + hi)
        if passes(mid):
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def main():
    t0 = time.time()
    data = {"equation": "theta'' = -beta theta' - sin(theta) + A cos(omega t) + tau",
            "method": "scipy DOP853 rtol=atol=1e-13 with the variational equations; Newton on the map; "
                      "brentq (xtol 1e-14) on 1 -+ tr M + det M; bisection on the unstable manifold's outcome",
            "cascade": {"damping": BETA, "drive_frequency": OMEGA, "start": 1.0, "points": cascade()},
            "retrapping": [{"damping": b, "torque": retrapping(b)} for b in (0.1, 0.3, 0.5, 0.8)]}
    for r in data["retrapping"]:
        print(f"retrapping beta={r['damping']} tau={r['torque']!r}")
    path = Path(__file__).with_name("continuation_reference.json")
    path.write_text(json.dumps(data, indent=1) + "\n")
    print(f"wrote {path} in {time.time() - t0:.0f} s")


if __name__ == "__main__":
    main()
