"""
Kapitza's inverted pendulum
===========================

A pivot vibrating vertically, y = a cos Ωt, changes gravity to
ε − aΩ² cos Ωt.  Fast enough (aΩ > √(2ε), Kapitza 1951) it makes the
upside-down state stable: released 0.3 rad from the top, the pendulum stays
up and wobbles about θ = π (top, animated); without the vibration it falls.
Below: the stability of the inverted state over (a, Ω), from the Floquet
multipliers of the orbit θ = π (:func:`pendula.periodic_orbit`; stable when
both lie on the unit circle), with the boundaries of the Mathieu equation's
stability tongues (pendula's characteristic values a₀(q) and b₁(q), with
δ = −4ε/Ω², q = 2a) and Kapitza's limit aΩ = √2.
"""

import math

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.animation import FuncAnimation

import pendula

a, W = 0.05, 40.0
t = np.linspace(0, 12, 121)
up = pendula.simulate(
    pendula.Scene(theta0=math.pi - 0.3, pivot_amplitude=a, pivot_frequency=W),
    t,
)
down = pendula.simulate(pendula.Scene(theta0=math.pi - 0.3), t)

fig, (axp, axt) = plt.subplots(
    1, 2, figsize=(8, 3.4), dpi=60, gridspec_kw={"width_ratios": [1, 1.6]}
)
axp.set(
    xlim=(-2.6, 2.6),
    ylim=(-1.4, 1.4),
    aspect="equal",
    xticks=[],
    yticks=[],
    title=f"vibrating pivot (a = {a}, Ω = {W:g}) | still pivot",
)
rods = [axp.plot([], [], lw=2, color=c)[0] for c in ("tab:blue", "0.5")]
bobs = [axp.plot([], [], "o", ms=9, color=c)[0] for c in ("tab:blue", "0.5")]
axt.plot(t, up.theta, color="tab:blue", label="vibrating pivot")
axt.plot(t, down.theta, color="0.5", label="still pivot")
axt.axhline(math.pi, ls="--", color="0.7", lw=0.8)
axt.set(xlabel="t", ylabel="θ", title="θ(t)")
axt.legend(fontsize=8)
fig.tight_layout()


def frame(k):
    for i, (tr, x0) in enumerate(((up, -1.2), (down, 1.2))):
        yp = (
            0.2 * math.cos(W * t[k]) if i == 0 else 0.0
        )  # the pivot's motion, exaggerated
        x, y = x0 + math.sin(tr.theta[k]), yp - math.cos(tr.theta[k])
        rods[i].set_data([x0, x], [yp, y])
        bobs[i].set_data([x], [y])
    return rods + bobs


anim = FuncAnimation(fig, frame, frames=len(t), interval=60, blit=True)

# %%
# The stability diagram of the inverted state (ε = 1).
amps = np.linspace(0.01, 0.8, 80)
freqs = np.linspace(1.5, 25.0, 71)
stable = np.zeros((len(freqs), len(amps)))
for i, w in enumerate(freqs):
    for j, aa in enumerate(amps):
        po = pendula.periodic_orbit(
            pendula.Scene(pivot_amplitude=float(aa), pivot_frequency=float(w)),
            guess=(math.pi, 0.0),
            rtol=1e-9,
            atol=1e-11,
        )
        stable[i, j] = np.max(np.abs(po.multipliers)) <= 1 + 1e-6
fig2, ax = plt.subplots(figsize=(6.4, 4.4))
ax.contourf(
    amps,
    freqs,
    stable,
    levels=[-0.5, 0.5, 1.5],
    colors=["white", "tab:green"],
    alpha=0.5,
)
fine = np.linspace(amps[0], amps[-1], 4000)
q = 2 * fine
for curve, label, style in (
    (pendula.mathieu_a(0, q), "δ = a₀(q)", "-"),
    (pendula.mathieu_b(1, q), "δ = b₁(q)", "--"),
):
    with np.errstate(invalid="ignore", divide="ignore"):
        w = np.where(curve < 0, np.sqrt(-4.0 / curve), np.nan)
    ax.plot(fine, w, "k" + style, lw=1, label=f"Mathieu: {label}")
ax.plot(
    amps, math.sqrt(2) / amps, ":", color="tab:red", label="Kapitza: aΩ = √2"
)
ax.set(
    xlabel="pivot amplitude a (in units of l)",
    ylabel="pivot frequency Ω",
    ylim=(freqs[0], freqs[-1]),
    title="inverted pendulum: stable (green) from Floquet multipliers",
)
ax.legend(fontsize=8, loc="upper right")
fig2.tight_layout()
plt.show()
