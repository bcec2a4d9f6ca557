"""
The driven pendulum: period doubling and chaos
===============================================

θ'' + β θ' + sin θ = A cos(Ωt) with β = 0.5, Ω = 2/3 (gallery scenes
``data/scenes/sweeps/driven_*``).  Top: the bifurcation diagram, the
velocity once per drive period after a transient, against the drive
amplitude A (:func:`pendula.sweep`, measure ``poincare``).  Bottom: the
largest Lyapunov exponent (measure ``lyapunov``): positive in the chaotic
bands, −β/2 where the orbit is a stable cycle with complex Floquet
multipliers.  Below, one chaotic orbit, animated.
"""

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.animation import FuncAnimation

import pendula

drive = pendula.Scene(damping=0.5, drive_frequency=2 / 3, rtol=1e-9,
                      atol=1e-11)
amps = np.linspace(0.9, 1.5, 61)
bif = pendula.sweep(drive, over={"drive_amplitude": amps}, measure="poincare",
                    transient=200 * 3 * np.pi,
                    samples=32)
lya = pendula.sweep(drive, over={"drive_amplitude": amps[::2]},
                    measure="lyapunov", transient=200.0,
                    t_max=800.0)

# the two panels one above the other, so that the figure fits the page's column
fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 7.6), layout="constrained")
ax1.plot(np.repeat(amps, bif.sizes["sample"]), bif.v.values.ravel(), ".k",
         ms=2)
ax1.set(xlabel="drive amplitude A", ylabel="v at t = 2πk/Ω",
        title="bifurcation diagram")
ax2.plot(lya.drive_amplitude, lya.lyapunov, ".-")
ax2.axhline(0, color="0.6", lw=0.8)
ax2.axhline(-0.25, color="0.6", lw=0.8, ls=":", label="−β/2")
ax2.set(xlabel="drive amplitude A", ylabel="λ1",
        title="largest Lyapunov exponent")
ax2.legend(fontsize=8)
plt.show()

# %%
# A chaotic orbit (A = 1.15)
# --------------------------
# The pendulum, and its stroboscopic points building the strange attractor in
# the (θ mod 2π, v) plane.

sc = drive.replace(drive_amplitude=1.15)
Tdrive = 2 * np.pi / (2 / 3)
t = 100 * Tdrive + np.linspace(0, 12 * Tdrive, 73)
tr = pendula.simulate(sc, t)
strobe = pendula.simulate(sc, 100 * Tdrive + Tdrive * np.arange(600))
wrap = (strobe.theta + np.pi) % (2 * np.pi) - np.pi

fig2, (axp, axs) = plt.subplots(1, 2, figsize=(8, 3.8), dpi=60)
axp.set(xlim=(-1.2, 1.2), ylim=(-1.2, 1.2), aspect="equal", xticks=[],
        yticks=[], title="A = 1.15")
rod, = axp.plot([], [], lw=2)
bob, = axp.plot([], [], "o", ms=10, color="tab:orange")
axs.set(xlim=(-np.pi, np.pi), ylim=(-3, 3), xlabel="θ mod 2π", ylabel="v",
        title="once per drive period")
pts, = axs.plot([], [], ".", ms=3, color="k")
fig2.tight_layout()


def frame(k):
    th = tr.theta[k]
    rod.set_data([0, np.sin(th)], [0, -np.cos(th)])
    bob.set_data([np.sin(th)], [-np.cos(th)])
    n = int(len(wrap) * (k + 1) / len(t))
    pts.set_data(wrap[:n], strobe.v[:n])
    return rod, bob, pts


anim = FuncAnimation(fig2, frame, frames=len(t), interval=80, blit=True)
plt.show()
