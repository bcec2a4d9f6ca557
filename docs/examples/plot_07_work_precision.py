"""
Work and precision of the integrators
=====================================

What accuracy costs (``pendula accuracy integrators``, here a small
version): the largest error in θ over 0 ≤ t ≤ 100 against the exact solution,
for a libration near the separatrix (v0 = 1.999), against the CPU time of the
run, for a few of pendula's integrators over a range of steps or
tolerances.  The conservative pendulum never needs an integrator (``auto``
uses the exact solution); the scene asks for one by name.  The full study,
with every method and the long-run energy, is in :doc:`/reports/cost`.
"""

import time

import matplotlib.pyplot as plt
import numpy as np

import pendula

sc = pendula.Scene(v0=1.999)
t = np.linspace(0, 100, 201)
exact = pendula.exact_motion(0.0, 1.999, 1.0, t)[0]


def run(**kw):
    best = np.inf
    for _ in range(3):
        t0 = time.process_time()
        tr = pendula.simulate(sc, t, **kw)
        best = min(best, time.process_time() - t0)
    return best, np.max(np.abs(tr.theta - exact))


fig, ax = plt.subplots(figsize=(8, 5))
for method in ("rk4", "yoshida6", "gauss6"):
    pts = [run(method=method, dt=dt) for dt in 0.2 / 2.0 ** np.arange(6)]
    ax.loglog(*zip(*pts), "s--", ms=4, label=method)
for method in ("dopri5", "dop853", "gsl-rk8pd"):
    pts = [run(method=method, rtol=r,
               atol=r * 1e-2) for r in 10.0 ** -np.arange(4, 13, 2)]
    ax.loglog(*zip(*pts), "o-", ms=4, label=method)
ax.set(xlabel="CPU time (s), best of 3",
       ylabel="max |θ − θ_exact| over the run",
       title="work-precision, libration v0 = 1.999")
ax.legend(fontsize=8)
fig.tight_layout()
plt.show()
