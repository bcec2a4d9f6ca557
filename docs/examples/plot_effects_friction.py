"""
Dry friction: the amplitude falls linearly, then the bob sticks
================================================================

Coulomb friction at the pivot, θ'' = −ε sin θ − μ sgn θ', takes a fixed
amount of energy per radian travelled, so each half swing loses (for small
angles) 2μ/ε of amplitude: the envelope is a straight line, not the
exponential of linear damping.  At the turning point where abs(ε sin θ) ≤ μ
the bob sticks for good.  The curve is pendula's integrated path (DOP853,
stopped and restarted at every v = 0 event); the dots are the exact turning
points from the energy balance ε (cos θb − cos θa) = μ abs(θb − θa)
(:func:`pendula.friction_turning_points`).
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula

mu = 0.04
sc = pendula.Scene(theta0=0.8, friction=mu, t_end=70.0, n_samples=3501)
tr = pendula.simulate(sc)
tp = pendula.friction_turning_points(sc)
lin = pendula.simulate(
    pendula.Scene(theta0=0.8, damping=0.05, t_end=70.0, n_samples=3501)
)

fig, ax = plt.subplots(figsize=(8, 4))
ax.plot(tr.t, tr.theta, lw=1.2, label=f"dry friction μ = {mu}")
ax.plot(lin.t, lin.theta, lw=0.8, color="0.6", label="linear damping β = 0.05")
ax.plot(
    tp.times,
    tp.angles,
    "o",
    ms=5,
    mfc="none",
    color="tab:red",
    label="exact turning points",
)
n = np.arange(len(tp.angles))
ax.plot(
    tp.times,
    (sc.theta0 - 2 * mu * n) * (-1.0) ** n,
    ":",
    color="tab:red",
    lw=0.8,
    label="θ0 − 2μn/ε (small-angle line)",
)
ax.axhspan(
    -np.arcsin(mu),
    np.arcsin(mu),
    color="tab:orange",
    alpha=0.15,
    label="stick zone |sin θ| ≤ μ",
)
ax.annotate(
    f"sticks at θ = {tp.stick_angle:.4f}, t = {tp.stick_time:.2f}",
    (tp.stick_time, tp.stick_angle),
    (tp.stick_time + 4, -0.55),
    arrowprops=dict(arrowstyle="->"),
)
ax.set(
    xlabel="t",
    ylabel="θ",
    title="Coulomb friction: linear decay and the stick",
)
ax.legend(fontsize=8, loc="upper right")
fig.tight_layout()
plt.show()
