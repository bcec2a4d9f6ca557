"""
Phase portraits
===============

Suzuki & Suzuki, Figs. 4 and 7 (gallery scenes ``fig4_phase_portrait`` and
``fig7_phase_near_separatrix``): the orbits of the conservative pendulum in
the (θ, v) plane.  Closed curves are librations, the wavy lines above and
below are rotations, and between them the separatrix v = ±2√ε cos(θ/2)
(ε = 1) joins the unstable equilibria θ = ±π.  The angle is wrapped to
[−π, π) for the rotations; every point is the exact solution.
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.4))
for v0 in [0.5, 1.0, 1.5, 1.9, 2.3, 2.8]:
    T = pendula.orbit(0.0, v0).period
    t = np.linspace(0, T, 800)
    th, v = pendula.exact_motion(0.0, v0, 1.0, t)
    for sign in (1, -1):
        w = (sign * th + np.pi) % (2 * np.pi) - np.pi
        # no line across the wrap
        w[np.abs(np.diff(w, append=w[-1])) > np.pi] = np.nan
        ax1.plot(w, sign * v, color="tab:blue" if v0 < 2 else "tab:green",
                 lw=1)
x = np.linspace(-np.pi, np.pi, 400)
ax1.plot(x, 2 * np.cos(x / 2), "k--", lw=1, label="separatrix")
ax1.plot(x, -2 * np.cos(x / 2), "k--", lw=1)
ax1.set(xlabel="θ (wrapped)", ylabel="v",
        title="librations (blue) and rotations (green)")
ax1.legend(loc="upper right", fontsize=8)

# next to the separatrix: v0 = 2 ∓ δ hugs it ever longer at the top
for delta in [1e-1, 1e-3, 1e-6]:
    for v0, c in ((2 - delta, "tab:blue"), (2 + delta, "tab:green")):
        o = pendula.orbit(0.0, v0)
        t = np.linspace(0, o.period, 2000)
        th, v = pendula.exact_motion(0.0, v0, 1.0, t)
        ax2.plot(th, v, color=c, lw=0.8,
                 alpha=0.4 + 0.2 * np.log10(1 / delta) / 2)
ax2.set(xlabel="θ", ylabel="v",
        title="v0 = 2 ∓ 10⁻¹, 10⁻³, 10⁻⁶ over one period")
fig.tight_layout()
plt.show()
