"""Long-run attractor labels of the driven damped pendulum by SciPy alone, on seeded random subsamples of
the 150 x 150 basin grids of tests/test_attractor_agreement.py.

theta'' = -sin(theta) - beta theta' + A cos(Omega t), grid theta0 in [-pi, pi], v0 in [-3, 3] (150 points
each), Omega = 2/3:

- ``1.07``: beta = 0.5, A = 1.07 (two period-2 attractors, intermixed basins);
- ``1.15``: beta = 0.2, A = 1.15 (two period-3 cycles 0.09-0.2 apart on the section, long transients).

Each sampled point is integrated over ``PERIODS`` drive periods by SciPy's DOP853 written from the equation
alone (all the sampled points at once as one vectorised system), once at rtol 1e-10 and once at rtol 1e-12
(atol the same).  The last 24 stroboscopic samples are read for the smallest period k <= 12 after which every
one recurs to within 1e-7 (angle modulo 2 pi); the cycle is then refined by a few Newton steps on the
stroboscopic map (SciPy again, finite differences) and stored by its points.  A point is *stable* when both
tolerances find the same cycle and a perturbation grows along its orbit by at most ``MAX_GROWTH`` (the
variational equations integrated with it; so an integration at rtol 1e-10 stays within about 1e-4 of it and
the label is resolved); a point with no recurring period by then (still on a transient), whose cycle moves
with the tolerance, or whose transient amplifies perturbations beyond that (its long-run label is not
determined by any practical tolerance: a chaotic transient) is not stable (the test compares the stable
points only).

    python data/gen_attractor_longrun_reference.py     (a few minutes on one core)
"""

import json
import math
import pathlib

import numpy as np
from scipy.integrate import solve_ivp

OUT = pathlib.Path(__file__).with_name("attractors") / "longrun_reference.json"
OMEGA = 2.0 / 3.0
T = 2 * math.pi / OMEGA
N_GRID = 150
#: case: (damping, amplitude, points sampled, drive periods)
CASES = {"1.07": (0.5, 1.07, 600, 400), "1.15": (0.2, 1.15, 600, 600)}
SEED = 20261204
TAIL = 24
#: the largest growth of a perturbation along a stable point's orbit
MAX_GROWTH = 1e6


def wrap(x):
    return (x + math.pi) % (2 * math.pi) - math.pi


def strobe(beta, A, theta, v, periods, rtol, chunk=150):
    """Samples after each drive period for every start (theta, v): arrays (npts, periods), and the largest
    log10 growth of a tangent vector (from a unit vector along theta, the variational equations integrated
    with the orbit) seen at the samples."""
    n = theta.size
    ths, vs, growth = np.empty((n, periods)), np.empty((n, periods)), np.empty(n)
    for lo in range(0, n, chunk):
        sl = slice(lo, min(n, lo + chunk))
        m = sl.stop - sl.start

        def rhs(t, y):
            th, w, a, b = y[:m], y[m:2 * m], y[2 * m:3 * m], y[3 * m:]
            return np.concatenate([w, -np.sin(th) - beta * w + A * math.cos(OMEGA * t), b,
                                   -np.cos(th) * a - beta * b])
        y = np.concatenate([theta[sl], v[sl], np.ones(m), np.zeros(m)])
        # the tangent vector's components are held to a relative tolerance: it grows by many orders
        atol = np.concatenate([np.full(2 * m, rtol), np.full(2 * m, 1e300)])
        sol = solve_ivp(rhs, (0.0, periods * T), y, method="DOP853", rtol=rtol, atol=atol,
                        t_eval=T * np.arange(1, periods + 1))
        assert sol.success, sol.message
        ths[sl], vs[sl] = sol.y[:m], sol.y[m:2 * m]
        growth[sl] = np.log10(np.hypot(sol.y[2 * m:3 * m], sol.y[3 * m:]).max(axis=1))
    return ths, vs, growth


def dist(t1, v1, t2, v2):
    return np.maximum(np.abs(wrap(t1 - t2)), np.abs(v1 - v2))


def newton_cycle(beta, A, th, v, k):
    """Refine a k-cycle point by Newton on the stroboscopic map (SciPy, rtol 1e-13, finite differences)."""
    def rhs(t, y):
        return [y[1], -math.sin(y[0]) - beta * y[1] + A * math.cos(OMEGA * t)]

    def P(x):
        s = solve_ivp(rhs, (0.0, k * T), x, method="DOP853", rtol=1e-13, atol=1e-13)
        return s.y[:, -1]
    x = np.array([th, v])
    for _ in range(8):
        f = P(x) - x
        f[0] = wrap(f[0])
        if np.max(np.abs(f)) < 1e-12:
            break
        J = np.empty((2, 2))
        for j in range(2):
            h = np.zeros(2)
            h[j] = 1e-7
            J[:, j] = (P(x + h) - P(x - h)) / 2e-7
        x = x - np.linalg.solve(J - np.eye(2), f)
    f = P(x) - x
    f[0] = wrap(f[0])
    pts = [x.copy()]
    for _ in range(k - 1):
        s = solve_ivp(rhs, (0.0, T), pts[-1], method="DOP853", rtol=1e-13, atol=1e-13)
        pts.append(s.y[:, -1])
    return [wrap(p[0]) for p in pts], [p[1] for p in pts], float(np.max(np.abs(f)))


def classify(ths, vs):
    """(period or 0, index of the last sample) per point from the tail of its samples."""
    th, v = wrap(ths[:, -TAIL:]), vs[:, -TAIL:]
    period = np.zeros(th.shape[0], dtype=int)
    for k in range(1, 13):
        todo = period == 0
        d = dist(th[:, k:], v[:, k:], th[:, :-k], v[:, :-k]).max(axis=1)
        period[todo & (d < 1e-7)] = k
    return period, th[:, -1], v[:, -1]


def main():
    rng = np.random.default_rng(SEED)
    axis_th, axis_v = np.linspace(-math.pi, math.pi, N_GRID), np.linspace(-3.0, 3.0, N_GRID)
    rec = {"equation": "theta'' = -sin(theta) - beta theta' + A cos(2 t / 3)", "grid": N_GRID,
           "theta0": [-math.pi, math.pi], "v0": [-3.0, 3.0], "seed": SEED, "cases": {}}
    for name, (beta, A, npts, periods) in CASES.items():
        flat = np.sort(rng.choice(N_GRID * N_GRID, npts, replace=False))
        i, j = np.divmod(flat, N_GRID)
        cycles, labels = [], []
        for rtol in (1e-10, 1e-12):
            ths, vs, growth = strobe(beta, A, axis_th[i], axis_v[j], periods, rtol)
            period, th_end, v_end = classify(ths, vs)
            lab = np.full(npts, -1)
            for p in np.flatnonzero(period > 0):
                k = int(period[p])
                for c_idx, c in enumerate(cycles):
                    if c["period"] == k and min(dist(th_end[p], v_end[p], np.array(c["theta"]),
                                                     np.array(c["v"]))) < 1e-5:
                        lab[p] = c_idx
                        break
                else:
                    cth, cv, res = newton_cycle(beta, A, th_end[p], v_end[p], k)
                    if res > 1e-9:
                        raise SystemExit(f"{name}: cycle at {th_end[p]}, {v_end[p]} does not close ({res})")
                    cycles.append({"period": k, "theta": cth, "v": cv, "residual": res})
                    lab[p] = len(cycles) - 1
            labels.append(lab)
            print(f"{name} rtol {rtol:g}: {np.bincount(lab + 1)} (first: unsettled)", flush=True)
        stable = (labels[0] == labels[1]) & (labels[0] >= 0) & (growth <= math.log10(MAX_GROWTH))
        rec["cases"][name] = {"damping": beta, "drive_amplitude": A, "drive_frequency": OMEGA,
                              "periods": periods, "i_theta0": i.tolist(), "j_v0": j.tolist(),
                              "labels": labels[1].tolist(), "stable": stable.astype(int).tolist(),
                              "log10_growth": np.round(growth, 3).tolist(), "max_growth": MAX_GROWTH,
                              "cycles": cycles}
        print(f"{name}: {len(cycles)} cycles, {stable.mean():.4f} of {npts} points stable; tolerances agree on "
              f"{(labels[0] == labels[1]).mean():.4f}; growth <= {MAX_GROWTH:g} on "
              f"{(growth <= math.log10(MAX_GROWTH)).mean():.4f}", flush=True)
    OUT.write_text(json.dumps(rec) + "\n")


if __name__ == "__main__":
    main()
