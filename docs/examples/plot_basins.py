"""
Attractors and their basins
===========================

The driven damped pendulum (β = 0.5, Ω = 2/3) at two drive amplitudes: each
initial state (θ0, v0) is coloured by the attractor of the stroboscopic map
its orbit ends on, found by recurrence without being told the attractors
(:func:`pendula.attractor_map`); the attractors' points are drawn
on the map.  At A = 1.35 two period-1 rotations, one each way, share the
plane; at A = 1.45 two period-2 rotations (a longer transient: their basins
are reached more slowly).  The title gives the basin entropy
and the uncertainty exponent α (α < 1: a fractal boundary, as Grebogi, Ott
and Yorke found on this system).
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula
from pendula import attractor_map

n = 56
grid = {"theta0": np.linspace(-np.pi, np.pi, n),
        "v0": np.linspace(-3.0, 3.0, n)}
fig, axes = plt.subplots(1, 2, figsize=(11, 4.8))
for ax, amp, transient in zip(axes, (1.35, 1.45), (300.0, 900.0)):
    sc = pendula.Scene(damping=0.5, drive_amplitude=amp,
                       drive_frequency=2 / 3, rtol=1e-9, atol=1e-11)
    am = attractor_map(sc, grid, transient=transient, samples=24)
    lab = am.dataset.attractor.values
    k = max(len(am.attractors), 1)
    ax.imshow(lab.T, origin="lower", extent=[-np.pi, np.pi, -3, 3],
              aspect="auto",
              cmap=plt.get_cmap("Pastel1", k), vmin=-0.5, vmax=k - 0.5,
              interpolation="nearest")
    for a in am.attractors:
        ax.plot(a.theta, a.v, "o", ms=6, mec="k",
                label=f"{a.kind}, period {a.period}: {a.fraction:.0%}")
    ax.set(xlabel="θ0", ylabel="v0",
           title=f"A = {amp}: S_b = {am.basin_entropy:.2f}, "
                 f"α = {am.uncertainty_exponent:.2f}")
    ax.legend(fontsize=7, loc="upper right")
fig.tight_layout()
plt.show()
