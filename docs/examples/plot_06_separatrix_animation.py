"""
The approach to the separatrix (animation)
==========================================

Five pendulums start at the bottom with v0 = 1.9, 1.99, 1.999 99, 2 and 2.01
(ε = 1).  Below v0 = 2 each swings back, but the closer v0 is to 2 the longer
it lingers next to the top: the period grows like the logarithm of 1/(2 − v0).  At v0 = 2
exactly the pendulum climbs towards the top forever (θ → π, reached only as
t → ∞), and above it, it turns over.  All five are the exact solution.
"""

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.animation import FuncAnimation

import pendula

v0s = [1.9, 1.99, 1.99999, 2.0, 2.01]
colors = ["tab:blue", "tab:cyan", "tab:purple", "k", "tab:green"]
t = np.linspace(0, 24, 61)
theta = np.array([pendula.exact_motion(0.0, v, 1.0, t)[0] for v in v0s])

fig, (axp, axt) = plt.subplots(2, 1, figsize=(6.4, 4.4),
                               gridspec_kw={"height_ratios": [1, 1.5]}, dpi=60)
axp.set(xlim=(-1.5, 13.5), ylim=(-1.3, 1.3), aspect="equal", xticks=[],
        yticks=[],
        title="v0 = " + ", ".join(f"{v:g}" for v in v0s))
rods, bobs = [], []
for i, c in enumerate(colors):
    x0 = 3 * i
    axp.plot([x0], [0], "k+", ms=6)
    rods.append(axp.plot([], [], color=c, lw=2)[0])
    bobs.append(axp.plot([], [], "o", color=c, ms=9)[0])
axt.set(xlim=(0, t[-1]), ylim=(-1, 7), xlabel="t", ylabel="θ")
axt.axhline(np.pi, color="0.7", lw=0.8, ls="--")
lines = [axt.plot([], [], color=c, lw=1.2)[0] for c in colors]
fig.tight_layout()


def frame(k):
    for i in range(len(v0s)):
        th = theta[i, k]
        x, y = 3 * i + np.sin(th), -np.cos(th)
        rods[i].set_data([3 * i, x], [0, y])
        bobs[i].set_data([x], [y])
        lines[i].set_data(t[: k + 1], theta[i, : k + 1])
    return rods + bobs + lines


anim = FuncAnimation(fig, frame, frames=len(t), interval=110, blit=True)
plt.show()
