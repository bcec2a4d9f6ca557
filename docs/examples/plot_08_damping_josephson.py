"""
Damping, torque and the Josephson junction
==========================================

Suzuki & Suzuki, sections 7 and 8.  Top: the well θ = 2πn a damped
pendulum (θ0 = 0) settles in, over a grid of starting velocities v0 and
damping β, by :func:`pendula.sweep` with the measure ``final_well`` (a
small version of the ``make demo`` map; each point stops as soon as its
energy is below the barrier of its well).  Bottom: with a constant torque τ
the mean velocity ⟨v⟩ against τ is the I–V curve of a Josephson junction
(RCSJ model): locked (⟨v⟩ = 0) up to τ = ε, running above, and on the way
down running until the retrapping torque near 4β/π: a hysteresis loop.
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula
import pendula.plot

s = pendula.Scene(damping=0.1, rtol=1e-8, atol=1e-10)
ds = pendula.sweep(s,
                   over={"v0": np.linspace(0.0, 4.0, 60),
                         "damping": np.linspace(0.02, 0.3, 36)},
                   measure="final_well")
print(ds)

# the two panels one above the other, so that the figure fits the page's column
fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 9.5), layout="constrained")
# one colour per well n (θ → 2πn), one tick each
pendula.plot.basins(ds, ax=ax1)
ax1.set(xlabel="v0", ylabel="damping β", title="basins of the damped pendulum")

beta = 0.1
r = pendula.iv_curve(pendula.Scene(damping=beta),
                     np.arange(0.0, 1.3001, 0.02), "both",
                     transient=100.0, t_max=200.0)
ax2.plot(r.torque, r.mean_velocity.sel(direction="up"), ".-",
         label="torque ramped up")
ax2.plot(r.torque, r.mean_velocity.sel(direction="down"), ".-",
         label="torque ramped down")
ax2.plot([0, 1.3], [0, 1.3 / beta], color="0.8", lw=0.8,
         label="ohmic line τ/β")
ax2.axvline(4 * beta / np.pi, color="0.6", ls=":",
            label="4β/π (Stewart–McCumber)")
ax2.set(xlabel="torque τ (bias current)", ylabel="⟨v⟩ (voltage)",
        ylim=(-0.5, 14),
        title=f"I–V loop, β = {beta}, ε = 1")
ax2.legend(fontsize=8)
plt.show()
