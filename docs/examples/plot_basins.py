"""
Attractors, their basins, and basin fractions over the drive
=============================================================

The driven damped pendulum (β = 0.5, Ω = 2/3).  Top and middle: each
initial state (θ0, v0) coloured by the attractor of the stroboscopic map its
orbit ends on (:func:`pendula.attractor_map`: orbits followed by recurrence
and stopped as soon as they are decided; periodic attractors confirmed by
Newton); the attractors' points are drawn on the map.  At A = 1.07 two
period-2 oscillations, mirror images of each other, share the plane with
intertwined basins; at A = 1.35 two period-1 rotations, one each way.  The
titles give the basin entropy and the uncertainty exponent α (α < 1: a
fractal boundary, as Grebogi, Ott and Yorke found on this system).  Bottom:
the fraction of the plane in each attractor's basin as the amplitude moves
(:func:`pendula.attractor_continuation`, attractors matched from one
amplitude to the next), stacked; what is left white is undecided.
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula
import pendula.plot

n = 60
grid = {"theta0": np.linspace(-np.pi, np.pi, n),
        "v0": np.linspace(-3.0, 3.0, n)}
# one panel a row, so that the figure fits the page's column at full size
fig, axes = plt.subplots(3, 1, figsize=(7, 15), layout="constrained")
for ax, amp in zip(axes, (1.07, 1.35)):
    sc = pendula.Scene(damping=0.5, drive_amplitude=amp,
                       drive_frequency=2 / 3)
    am = pendula.attractor_map(sc, grid)
    pendula.plot.basins(am, ax=ax)
    ax.set_title(f"A = {amp}: S_b = {am.basin_entropy:.2f}, "
                 f"α = {am.uncertainty_exponent:.2f}")

small = {"theta0": np.linspace(-np.pi, np.pi, 24),
         "v0": np.linspace(-3.0, 3.0, 24)}
ds = pendula.attractor_continuation(
    pendula.Scene(damping=0.5, drive_frequency=2 / 3), small,
    "drive_amplitude", np.linspace(1.0, 1.5, 21))
pendula.plot.fractions(ds, ax=axes[2])
axes[2].set_title("basin fractions, attractors continued")
plt.show()
