"""
θ(t) below, at and above the separatrix
========================================

Suzuki & Suzuki, Figs. 5 and 11 (gallery scenes ``fig5a_theta_t_libration``,
``fig5b_theta_t_near_separatrix`` and ``fig11_theta_t_rotation``): the angle of
the conservative pendulum (ε = 1, θ0 = 0) for starting velocities below
v0 = 2 (libration), next to it and above it (rotation).  Every curve is the
exact solution through Jacobi elliptic functions: no integrator is involved,
and v0 = 2 exactly climbs towards π forever.
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula

t = np.linspace(0, 30, 1501)
groups = {
    "libration": [1.7, 1.8, 1.9, 1.95],
    "near the separatrix": [1.99, 1.9999, 2.0, 2.0001, 2.01],
    "rotation": [2.1, 2.5, 3.0],
}
# one panel a row, so that the figure fits the page's column at full size
fig, axes = plt.subplots(3, 1, figsize=(7, 8.4), sharex=True,
                         layout="constrained")
for ax, (title, v0s) in zip(axes, groups.items()):
    for v0 in v0s:
        tr = pendula.simulate(pendula.Scene(v0=v0), t)
        ax.plot(tr.t, tr.theta, label=f"v0 = {v0:g}")
    ax.set_title(f"{title} ({tr.method})")
    ax.set_ylabel("θ (rad)")
    ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5))
axes[-1].set_xlabel("t (units of 1/√ε)")
plt.show()
