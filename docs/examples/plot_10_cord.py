"""
The flexible cord: flips and flights
====================================

Garfinkel (1957): the bob hangs on a cord that goes slack when its tension
m l (θ'² + ε cos θ) vanishes.  It then flies on a parabola, re-enters the
circle with an inelastic jerk that removes the radial velocity, and goes on
with a new energy ξ' = f(ξ), ξ = (θ'² − 2ε cos θ)/(3ε) (gallery scenes
``cord_*``).  Everything here comes from simulated flips, not from the
formula: the map measured by one flip per point lies on Garfinkel's f, and
the scene ``cord_example_0777`` (ξ(0) = 0.777) flips on without end.  The
animation shows its first flights, the cord slack (dashed) in flight.
"""

import warnings

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.animation import FuncAnimation

import pendula

# the map from simulated flips: start on the circle at the bottom with
# energy xi
xs = np.linspace(0.02, 0.98, 25)
after = []
for xi in xs:
    # xi = (v0^2 - 2)/3 at theta = 0, eps = 1
    v0 = np.sqrt(3 * xi + 2)
    # the run stops after its one flip: later times are NaN, as it warns
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        tr = pendula.simulate(pendula.Scene(cord="flexible", v0=v0, t_end=12,
                                            n_samples=3, max_flips=1))
    after.append(tr.flips["xi_after"][0])
# the two panels one above the other, so that the figure fits the page's column
fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(6.5, 10), layout="constrained")
xx = np.linspace(0, 1, 400)
ax1.plot(xx, pendula.flip_map(xx), color="0.3",
         label="f(ξ), Garfinkel's closed form")
ax1.plot(xs, after, "o", mfc="none", color="tab:red",
         label="one simulated flip each")
ax1.axhline(0, color="0.8", lw=0.6)
ax1.set(xlabel="ξ before the flip", ylabel="ξ after", title="the flip map")
ax1.legend(fontsize=8)

sc = pendula.Scene(cord="flexible", v0=2.0811054754625005, t_end=40,
                   n_samples=4001)
tr = pendula.simulate(sc)
fly = tr.r < 1 - 1e-12
ax2.plot(np.where(fly, np.nan, tr.x), np.where(fly, np.nan, tr.y), lw=0.8,
         label="taut, on the circle")
ax2.plot(np.where(fly, tr.x, np.nan), np.where(fly, tr.y, np.nan), "r--",
         lw=0.8, label="slack, in flight")
ax2.set(aspect="equal", xlabel="x / l", ylabel="y / l",
        title=f"ξ(0) = 0.777: {tr.stats['flips']} flips by t = 40")
ax2.legend(fontsize=8, loc="lower right")
plt.show()

# %%
# The first flips, animated
# -------------------------

t = np.linspace(0, 16, 161)
an = pendula.simulate(sc.replace(t_end=16, n_samples=161))
fig2, ax = plt.subplots(figsize=(4.5, 4.5), dpi=72)
a = np.linspace(0, 2 * np.pi, 200)
ax.plot(np.cos(a), np.sin(a), color="0.85", lw=0.8)
ax.plot([0], [0], "k+")
ax.set(xlim=(-1.2, 1.2), ylim=(-1.2, 1.2), aspect="equal", xticks=[],
       yticks=[])
cord, = ax.plot([], [], lw=2)
bob, = ax.plot([], [], "o", ms=10, color="tab:orange")
trail, = ax.plot([], [], color="tab:red", lw=0.8, alpha=0.6)
label = ax.text(-1.15, 1.08, "", fontsize=9)
fig2.tight_layout()


def frame(k):
    slack = an.r[k] < 1 - 1e-12
    cord.set_data([0, an.x[k]], [0, an.y[k]])
    cord.set_linestyle("--" if slack else "-")
    cord.set_color("0.5" if slack else "tab:blue")
    bob.set_data([an.x[k]], [an.y[k]])
    j = max(0, k - 15)
    trail.set_data(an.x[j: k + 1], an.y[j: k + 1])
    label.set_text(f"t = {an.t[k]:5.1f}  "
                   f"{'slack: free flight' if slack else 'taut'}")
    return cord, bob, trail, label


anim = FuncAnimation(fig2, frame, frames=len(an.t), interval=70, blit=True)
plt.show()
