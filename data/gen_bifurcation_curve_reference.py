"""Reference points on the fold and period-doubling curves of the damped driven pendulum, with scipy.

    theta'' = -beta theta' - sin(theta) + A cos(omega t) + tau,    beta = 0.5

Written independently of pendula (no import of it): scipy's DOP853 at rtol = atol = 1e-12 on the
equation, its variational equations in the state and its derivative in A, Newton's method on the
stroboscopic map, and brentq (a safeguarded bisection, xtol 1e-14) on the multipliers' condition.

1. Period doubling (a multiplier -1) of the asymmetric period-1 orbit of the cascade at omega = 2/3
   (A = 1.0664): at each omega the orbit is found by Newton in (theta, v) at fixed A, and A solved by
   brentq on 1 + tr M + det M (zero where M has the eigenvalue -1).
2. Fold of the period-1 oscillation (a multiplier +1; the two folds of the resonance's hysteresis at
   omega = 0.5, A = 0.869 and 0.760): at a fold the orbit's A has an extremum along the branch, so the
   branch is parametrised by the coordinate s along the last fold's critical eigenvector q (tangent to
   the branch at the fold, so regular through it): at each s Newton in (w, A) solves P(x; A) = x for
   x = x0 + s q + w q', and brentq solves det(M - I) = 0 in s.
3. Pitchfork of the symmetric period-1 orbit (A = 1.0043 at omega = 2/3): the symmetric orbit as a
   fixed point of the half-period map G (Newton), A by brentq on 1 + tr DG + det DG (DG's eigenvalue -1
   is the monodromy DG^2's +1 where the symmetry breaks), omega = 0.6 to 0.7.
   (`python data/gen_bifurcation_curve_reference.py pitchfork` recomputes this part alone.)
4. The overdamped-limit check of the Shapiro steps is a closed form (Bessel functions): not here.
   The steps' edges at finite frequency (item 3 of the output) are folds of the locked orbit (winding n
   per drive period) in the torque at fixed A and omega: parametrised by theta as in 2, with the
   torque as the unknown instead of A.

Run: python data/gen_bifurcation_curve_reference.py   (about three minutes)
Output: data/bifurcation_curve_reference.json.
"""

from __future__ import annotations

import json
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

RTOL = ATOL = 1e-12


def rhs(t, y, A, omega, beta, tau, which):
    """The equation, its variational equations (M columns) and the derivative in A or tau."""
    th, v = y[0], y[1]
    c = -math.cos(th)
    drive = math.cos(omega * t) if which == "A" else 1.0
    out = [v, -beta * v - math.sin(th) + A * math.cos(omega * t) + tau]
    for j in range(2):                       # the columns of M
        a, b = y[2 + 2 * j], y[3 + 2 * j]
        out += [b, c * a - beta * b]
    a, b = y[6], y[7]                        # d(theta, v)/d(A or tau)
    out += [b, c * a - beta * b + drive]
    return out


def flow(x, A, omega, beta, tau, k=1, which="A"):
    """(P(x), M, dP/dA or dP/dtau) over k drive periods."""
    T = k * 2 * math.pi / omega
    y0 = [x[0], x[1], 1.0, 0.0, 0.0, 1.0, 0.0, 0.0]
    s = solve_ivp(rhs, (0.0, T), y0, method="DOP853", rtol=RTOL, atol=ATOL, args=(A, omega, beta, tau, which))
    y = s.y[:, -1]
    return y[:2], np.array([[y[2], y[4]], [y[3], y[5]]]), y[6:8]


def converged(step, x, r):
    """Newton has converged: a step at the flow's noise (1e-13 relative), or a residual at it with a step
    that no longer shrinks (the Jacobian's conditioning turns the noise into steps of about 1e-12)."""
    return np.max(np.abs(step)) < 1e-13 * (1 + np.max(np.abs(x))) or (
        np.max(np.abs(r)) < 1e-12 and np.max(np.abs(step)) < 1e-10)


def orbit(x, A, omega, beta, tau=0.0, winding=0):
    """Newton in (theta, v) at fixed A: a fixed point of the map (advancing `winding` turns)."""
    x = np.array(x, dtype=float)
    for _ in range(40):
        P, M, _ = flow(x, A, omega, beta, tau)
        r = P - x - [2 * math.pi * winding, 0.0]
        dx = np.linalg.solve(M - np.eye(2), -r)
        x = x + dx
        if np.max(np.abs(dx)) < 1e-13 * (1 + np.max(np.abs(x))):
            break
    else:
        raise RuntimeError("Newton did not converge")
    P, M, _ = flow(x, A, omega, beta, tau)
    return x, M


def minus_one_point(solve, A0, x0, omega, beta, warm):
    """The A near A0 where the matrix X of the orbit solve(x, A, omega, beta) -> (x, X) has the eigenvalue -1:
    brentq on 1 + tr X + det X in a bracket around A0, widened until it changes sign (with `warm` the orbit
    is found at A0 first, the start of the bracket's ends).  Returns (A, x, X)."""
    state = {"x": np.array(x0, dtype=float)}

    def g(A):
        x, X = solve(state["x"], A, omega, beta)
        state["x"] = x
        return 1.0 + np.trace(X) + np.linalg.det(X)
    width = 0.005
    for _ in range(8):                      # a bracket around the guess A0, widened until g changes sign
        state["x"] = np.array(x0, dtype=float)
        if warm:
            g(A0)
        lo, hi = A0 - width, A0 + width
        glo, ghi = g(lo), g(hi)
        if glo * ghi < 0:
            break
        width *= 2
    else:
        raise RuntimeError(f"no sign change of 1 + tr X + det X near A = {A0} at omega = {omega}")
    A = brentq(g, lo, hi, xtol=1e-14, rtol=4 * np.finfo(float).eps, maxiter=200)
    x, X = solve(state["x"], A, omega, beta)
    return A, x, X


def pd_point(A0, x0, omega, beta):
    """A on the period-doubling curve at omega: the monodromy M of the orbit has the multiplier -1."""
    A, x, M = minus_one_point(orbit, A0, x0, omega, beta, warm=True)
    return A, x, np.linalg.eigvals(M)


def half_orbit(x, A, omega, beta):
    """Newton on the half-period map G(x) = (2 pi m - theta(T/2), -v(T/2)) at fixed A: the symmetric orbit.
    Returns (x, DG)."""
    T = 2 * math.pi / omega
    x = np.array(x, dtype=float)

    def half(x):
        s = solve_ivp(rhs, (0.0, T / 2), [x[0], x[1], 1, 0, 0, 1, 0, 0], method="DOP853", rtol=RTOL, atol=ATOL,
                      args=(A, omega, beta, 0.0, "A"))
        y = s.y[:, -1]
        return y[:2], -np.array([[y[2], y[4]], [y[3], y[5]]])
    y, _ = half(x)
    m = round((y[0] + x[0]) / (2 * math.pi))
    for _ in range(40):
        y, DG = half(x)
        r = np.array([2 * math.pi * m - y[0] - x[0], -y[1] - x[1]])
        dx = np.linalg.solve(DG - np.eye(2), -r)
        x = x + dx
        if converged(dx, x, r):
            break
    else:
        raise RuntimeError("Newton did not converge")
    return x, half(x)[1]


def pitchfork_point(A0, x0, omega, beta):
    """A on the pitchfork curve at omega: the half-period map's DG has the eigenvalue -1 (M = DG^2's +1)."""
    A, x, DG = minus_one_point(half_orbit, A0, x0, omega, beta, warm=False)
    return A, x, np.linalg.eigvals(DG @ DG)


def follow_in_omega(point, x0, A0, kept, beta, t0, label):
    """A curve of `point` (pd_point or pitchfork_point) from (x0, A0) at omega = 2/3, in steps of 0.01/3
    down to 0.6 and up to 0.7; each step's guess of A extrapolates the last two.  Returns the points at
    the omegas in `kept`."""
    out = []
    for omegas in ([2 / 3] + [round(2 / 3 - i * 0.01 / 3, 12) for i in range(1, 21)],
                   [round(2 / 3 + i * 0.01 / 3, 12) for i in range(1, 11)]):
        x, A = np.array(x0), A0
        last = []
        for omega in omegas:
            guess = A if len(last) < 2 else last[-1][1] + (omega - last[-1][0]) * (
                (last[-1][1] - last[-2][1]) / (last[-1][0] - last[-2][0]))
            A, x, mu = point(guess, x, omega, beta)
            last.append((omega, A))
            if min(abs(omega - w) for w in kept) < 1e-9:
                out.append({"omega": float(omega), "A": A, "theta": x[0], "v": x[1],
                            "multipliers": sorted(np.real(mu).tolist())})
                print(label, omega, A, time.time() - t0)
    return out


def pitchforks(beta, t0):
    """The pitchfork curve from A = 1.004319 at omega = 2/3 (the symmetric orbit theta -1.07195, v 1.89723)."""
    return follow_in_omega(pitchfork_point, [-1.07195, 1.89723], 1.0043195, (2 / 3, 0.64, 0.6, 0.7),
                           beta, t0, "pitchfork")


def branch_at(s, w, p, omega, beta, fixed, which, winding=0, c=(0.0, 0.0), e=(1.0, 0.0)):
    """Newton in (w, p) at the coordinate s along the unit direction e through c: the state
    x = c + s e + w f (f = e turned by 90 degrees) with P(x; p) = x + (2 pi winding, 0); p is A (with the
    torque `fixed`) or the torque tau (with A `fixed`).  Returns (w, p, M, x)."""
    c, e = np.asarray(c, dtype=float), np.asarray(e, dtype=float)
    f = np.array([-e[1], e[0]])
    z = np.array([w, p], dtype=float)
    for _ in range(100):
        A, tau = (z[1], fixed) if which == "A" else (fixed, z[1])
        x = c + s * e + z[0] * f
        P, M, dP = flow(x, A, omega, beta, tau, which=which)
        r = P - x - [2 * math.pi * winding, 0.0]
        J = np.column_stack([(M - np.eye(2)) @ f, dP])
        dz = np.linalg.solve(J, -r)
        big = np.max(np.abs(dz))
        if big > 0.05:                 # a damped step far from the root (the map is strongly nonlinear)
            dz = dz * (0.05 / big)
        z = z + dz
        if converged(dz, z, r):
            break
    else:
        raise RuntimeError("Newton did not converge")
    A, tau = (z[1], fixed) if which == "A" else (fixed, z[1])
    x = c + s * e + z[0] * f
    _, M, _ = flow(x, A, omega, beta, tau)
    return z[0], z[1], M, x


def branch_at_theta(theta, v, p, omega, beta, fixed, which, winding=0):
    """branch_at with the section's theta as the coordinate: Newton in (v, p).  Returns (v, p, M)."""
    w, p, M, _ = branch_at(theta, v, p, omega, beta, fixed, which, winding)
    return w, p, M


def fold_point(x0, p0, q, omega, beta, fixed=0.0, which="A", winding=0, ds=0.005):
    """A fold near x0 (p0): an extremum of p along the branch, parametrised by the coordinate s along q (the
    fold's critical eigenvector, tangent to the branch there, so the parametrisation is regular through
    it): brentq on det(M - I) in s."""
    q = np.asarray(q, dtype=float) / np.linalg.norm(q)
    state = {"w": 0.0, "p": p0}

    def g(s):
        w, p, M, x = branch_at(s, state["w"], state["p"], omega, beta, fixed, which, winding, c=x0, e=q)
        state["w"], state["p"], state["x"], state["M"] = w, p, x, M
        return np.linalg.det(M - np.eye(2))
    # a bracket: steps of ds from 0 both ways until det(M - I) changes sign
    g0 = g(0.0)
    s0 = (0.0, dict(state))
    for k in range(1, 41):
        found = False
        for sgn in (1.0, -1.0):
            state.update(s0[1])
            a, b = sgn * (k - 1) * ds, sgn * k * ds
            if (g(a) > 0) != (g(b) > 0):
                found = True
                break
        if found:
            break
    else:
        raise RuntimeError("no sign change of det(M - I)")
    a, b = sorted((a, b))
    g(a)
    s = brentq(g, a, b, xtol=1e-14, rtol=4 * np.finfo(float).eps, maxiter=200)
    g(s)
    mu, V = np.linalg.eig(state["M"])
    qn = np.real(V[:, np.argmin(np.abs(mu - 1))])
    return state["p"], state["x"], mu, qn * np.sign(qn @ q)


def main():
    t0 = time.time()
    beta = 0.5
    path = Path(__file__).with_name("bifurcation_curve_reference.json")
    if sys.argv[1:] == ["pitchfork"]:       # only the pitchfork curve, into the existing file
        out = json.loads(path.read_text())
        out["pitchfork"] = pitchforks(beta, t0)
        path.write_text(json.dumps(out, indent=1))
        return
    out = {"beta": beta, "rtol": RTOL, "method": "scipy DOP853 + Newton on the map + brentq (xtol 1e-14)"}
    # 1. period doubling of the asymmetric orbit, from A = 1.066373 at omega = 2/3 (theta -0.2215, v 1.9597);
    # the orbit is followed from omega to omega by reusing the last state
    out["period_doubling"] = follow_in_omega(pd_point, [-0.221475, 1.95966], 1.0663729,
                                             (2 / 3, 0.64, 0.62, 0.6, 0.68, 0.7), beta, t0, "pd")
    # 2. the two folds of the period-1 oscillation at omega = 0.5 and up to 0.6 (the cusp is near 0.6129)
    fold = []
    # the critical eigenvectors at the start from the Jacobian of the map (not needed precisely: a
    # direction transverse to the branch's normal)
    for name, (x, A) in {"upper": ((1.49244, 0.347875), 0.8688577), "lower": ((1.06945, 1.37062), 0.7602568)}.items():
        x = np.array(x)
        _, M, _ = flow(x, A, 0.5, beta, 0.0)
        mu, V = np.linalg.eig(M)
        q = np.real(V[:, np.argmin(np.abs(mu - 1))])
        for omega in (round(0.5 + 0.0025 * i, 12) for i in range(41)):    # small steps from the last fold
            A, x, mu, q = fold_point(x, A, q, omega, beta, which="A")
            if min(abs(omega - w) for w in (0.5, 0.54, 0.58, 0.6)) < 1e-9:
                fold.append({"fold": name, "omega": float(omega), "A": A, "theta": x[0], "v": x[1],
                             "multipliers": sorted(np.real(mu).tolist())})
                print("fold", name, omega, A, time.time() - t0)
    out["fold"] = fold
    out["pitchfork"] = pitchforks(beta, t0)
    Path(__file__).with_name("bifurcation_curve_reference.json").write_text(json.dumps(out, indent=1))
    print(f"{time.time() - t0:.0f} s")


if __name__ == "__main__":
    main()
