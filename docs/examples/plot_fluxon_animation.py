"""
A fluxon circling an annular junction (animation)
=================================================

A long Josephson junction closed on itself is a ring of pendula: 80
pendula 1/4 of a Josephson length apart (springs K = 16) with a 2π twist
on the closing spring, which traps one fluxon.  The bias γ = 0.1 pushes it
round against the damping α = 0.05.  Top: each pendulum of the ring drawn
at its place along the junction, its rod turned by its phase φ; where the
rods swing over the top is the fluxon.  Bottom: the voltage φ_t along the
junction, the fluxon's moving pulse (the ripples behind it are the
lattice's radiation, absent in the continuum).  Starting at rest, it speeds
up over a few 1/α to its terminal speed, which :func:`pendula.fluxon_velocity` measures
beside McLaughlin and Scott's power balance u = 1/√(1 + (4α/πγ)²).
"""

import math

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.animation import FuncAnimation

import pendula

plt.rcParams["font.size"] = 12      # >= 9 px at the animation's 60 dpi
n, a, alpha, gamma = 80, 0.25, 0.05, 0.1
off = np.zeros((n, n))
off[n - 1, 0], off[0, n - 1] = -2 * np.pi, 2 * np.pi
ring = pendula.Network(n, topology="ring", strength=1 / a**2, offset=off,
                       damping=alpha, bias=gamma)
x = a * np.arange(n)
t = np.linspace(0, 90, 61)
run = ring.simulate(t, phi0=4 * np.arctan(np.exp(x - x[-1] / 2)),
                    rtol=1e-8, atol=1e-10)
phi, v = run.phi.values, run.v.values
r = pendula.fluxon_velocity([gamma], alpha, length=n * a, spacing=a)
u, ms = float(r.speed[0]), float(r.power_balance[0])

fig, (axp, axv) = plt.subplots(2, 1, figsize=(6.4, 4.4), dpi=60,
                               gridspec_kw={"height_ratios": [1, 1.2]})
axp.set(xlim=(-0.5, x[-1] + 0.5), ylim=(-1.3, 1.3), yticks=[],
        xlabel="position along the junction (λ_J)",
        title=f"terminal speed {u:.3f} (lattice), {ms:.3f} (power balance)")
rods = [axp.plot([], [], color="tab:blue", lw=1.2)[0] for _ in range(n)]
bobs = axp.plot([], [], "o", color="tab:blue", ms=3)[0]
axv.set(xlim=(x[0], x[-1]), ylim=(-0.2, 1.2 * max(1e-3, v.max())),
        xlabel="position along the junction (λ_J)", ylabel="voltage φ_t")
pulse = axv.plot([], [], color="tab:red", lw=1.5)[0]
stamp = axv.text(0.02, 0.85, "", transform=axv.transAxes)
fig.tight_layout()


def frame(k):
    bx, by = x + 0.9 * np.sin(phi[k]), -0.9 * np.cos(phi[k])
    for i, rod in enumerate(rods):
        rod.set_data([x[i], bx[i]], [0, by[i]])
    bobs.set_data(bx, by)
    pulse.set_data(x, v[k])
    stamp.set_text(f"t = {t[k]:.0f} / ω_p")
    return rods + [bobs, pulse, stamp]


anim = FuncAnimation(fig, frame, frames=len(t), interval=80, blit=True)
plt.show()
