"""
Air drag against linear damping
===============================

Quadratic drag, θ'' = −sin θ − γ θ' abs(θ'), is strong at high speed and vanishes
quickly as the speed falls; linear damping, −β θ', keeps the same rate.  With
the two matched on the first swing, drag wins early and loses late: the
amplitude under drag falls like 1/(1 + c t) (each swing loses a fixed
fraction of its amplitude squared), under linear damping like exp(−βt/2).
pendula integrates drag in stretches between the v = 0 events, with the sign
of the drag term fixed on each (never a smoothed abs(v)).
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula

t = np.linspace(0, 150, 7501)
drag = pendula.simulate(pendula.Scene(theta0=2.5, drag=0.15), t)
damp = pendula.simulate(pendula.Scene(theta0=2.5, damping=0.08), t)


def maxima(tr):
    k = (
        np.flatnonzero(
            (tr.theta[1:-1] > tr.theta[:-2]) & (tr.theta[1:-1] >= tr.theta[2:])
        )
        + 1
    )
    return tr.t[k], tr.theta[k]


fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.8))
ax1.plot(t, drag.theta, lw=0.8, label="drag γ = 0.15")
ax1.plot(t, damp.theta, lw=0.8, label="linear β = 0.08")
ax1.set(xlabel="t", ylabel="θ", xlim=(0, 60), title="the first swings")
ax1.legend(fontsize=8)
for tr, lab in ((drag, "drag"), (damp, "linear")):
    tm, am = maxima(tr)
    ax2.semilogy(tm, am, "o-", ms=3, lw=0.8, label=lab)
ax2.set(
    xlabel="t",
    ylabel="amplitude (maxima of θ)",
    title="amplitude: 1/(1 + ct) against exp(−βt/2)",
)
ax2.legend(fontsize=8)
fig.tight_layout()
plt.show()
