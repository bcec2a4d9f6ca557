"""Reference attractor labels of the driven damped pendulum for tests/test_attractors_recurrence.py.

theta'' = -sin(theta) - 0.5 theta' + A cos(2 t / 3) on grids over theta0 in [-pi, pi], v0 in [-3, 3]
(A = 1.07: 40 x 40 and 150 x 150, the two period-2 attractors; A = 1.35: 30 x 30 and 150 x 150, the two
period-1 rotations; the 150 x 150 grids are fine enough for the attractor map's coarse-to-fine levels).

Each point is labelled by a long run without early stopping: 1200 time units (rounded up to whole drive
periods), then 64 stroboscopic samples read for recurrence (``attractor_map(method='samples')``), once at
rtol 1e-10 and once at rtol 1e-12; a point whose label moves between the two, or that has not settled on a
cycle by then (still on a chaotic transient), is marked unstable (the test compares the stable points only).
Labels are stored as the attractor's cycle (its points on the section), not as a number, so a test matches
attractors by position.  Every reference cycle is checked here against
SciPy's DOP853 at rtol 1e-13 written from the equation alone: k drive periods from a cycle point must come
back to it (residual stored; a cycle whose residual exceeds 1e-8 stops the script).

    python data/gen_attractor_reference.py     (about ten minutes on 2 cores)
"""

import json
import math
import pathlib

import numpy as np
from scipy.integrate import solve_ivp

import pendula

OUT = pathlib.Path(__file__).with_name("attractors") / "reference_labels.json"
#: case name: (amplitude, points per axis)
CASES = {"1.07": (1.07, 40), "1.35": (1.35, 30), "1.07 150": (1.07, 150), "1.35 150": (1.35, 150)}


def flow_residual(A, theta, v, k):
    """max |x(k T) - x(0)| (angle modulo 2 pi) by SciPy from the equation alone."""
    w = 2.0 / 3.0

    def rhs(t, y):
        return [y[1], -math.sin(y[0]) - 0.5 * y[1] + A * math.cos(w * t)]
    sol = solve_ivp(rhs, (0.0, k * 2 * math.pi / w), [theta, v], method="DOP853", rtol=1e-13, atol=1e-13)
    th, vv = sol.y[0, -1], sol.y[1, -1]
    dth = (th - theta + math.pi) % (2 * math.pi) - math.pi
    return max(abs(dth), abs(vv - v))


def main():
    rec = {"equation": "theta'' = -sin(theta) - 0.5 theta' + A cos(2 t / 3)", "transient": 1200.0, "samples": 64,
           "cases": {}}
    for a_text, (A, n) in CASES.items():
        sc = pendula.Scene(damping=0.5, drive_amplitude=A, drive_frequency=2 / 3)
        grid = {"theta0": np.linspace(-math.pi, math.pi, n), "v0": np.linspace(-3.0, 3.0, n)}
        maps = [pendula.attractor_map(sc, grid, transient=1200.0, samples=64, rtol=r, atol=r * 1e-2, threads=2,
                                      progress=True)
                for r in (1e-10, 1e-12)]
        cycles = []          # distinct cycles over both runs, by position
        labels = []
        for m in maps:
            ids = {}
            for a in m.attractors:
                if a.kind != "periodic":
                    # orbits still on a chaotic transient after the long run: no reference label
                    ids[a.label] = -1
                    print(f"A = {A}, n = {n}: {a.fraction * n * n:.0f} points not settled on a cycle")
                    continue
                for j, c in enumerate(cycles):
                    if c["period"] == a.period and min(abs(c["theta"][0] - t) + abs(c["v"][0] - v)
                                                       for t, v in zip(a.theta, a.v)) < 1e-5:
                        ids[a.label] = j
                        break
                else:
                    res = flow_residual(A, float(a.theta[0]), float(a.v[0]), a.period)
                    if res > 1e-8:
                        raise SystemExit(f"A = {A}: cycle {a.theta[0]}, {a.v[0]} does not close (SciPy: {res})")
                    cycles.append({"period": a.period, "theta": a.theta.tolist(), "v": a.v.tolist(),
                                   "scipy_residual": res})
                    ids[a.label] = len(cycles) - 1
            lab = m.dataset.attractor.values
            labels.append(np.where(lab >= 0, np.vectorize(lambda x: ids.get(int(x), -1))(lab), -1))
        stable = (labels[0] == labels[1]) & (labels[0] >= 0)
        rec["cases"][a_text] = {"n": n, "cycles": cycles, "labels": labels[0].tolist(),
                                "stable": stable.astype(int).tolist()}
        print(f"A = {A}: {len(cycles)} cycles, {stable.mean():.4f} of the points stable under rtol 1e-12")
    OUT.parent.mkdir(exist_ok=True)
    OUT.write_text(json.dumps(rec) + "\n")


if __name__ == "__main__":
    main()
