"""
Two coupled pendula and a kink on a chain
=========================================

Left: two equal pendula joined by a weak spring (K = 0.05) trade their
energy back and forth; the first is let go from 0.3 rad, the second from
rest.  The energy crosses over completely in half a beat period
π / (ω₂ − ω₁) (the dashed line), ω₁ = 1 and ω₂ = √(1 + 2K) the two normal
modes.  Right: a ring of 60 pendula (the discrete sine-Gordon equation,
K = 1.5) with one trapped kink, a 2π twist carried by the closing spring's
offset.  A bias τ = 0.05 pushes the kink round against a damping of 0.05:
it speeds up to its terminal velocity and circles the ring.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

import pendula

# --- two coupled pendula: the energy of each
k = 0.05
pair = pendula.Network(2, topology="pair", strength=k)
half_beat = math.pi / (math.sqrt(1 + 2 * k) - 1)
t = np.linspace(0, 2.2 * half_beat, 2001)
run = pair.simulate(t, phi0=[0.3, 0.0])
phi, v = run.phi.values, run.v.values
# each pendulum's own energy (the spring's share is small at K = 0.05)
own = 0.5 * v ** 2 + 1 - np.cos(phi)

# --- a kink on a ring: the closing spring holds a 2π twist
n, kr = 60, 1.5
off = np.zeros((n, n))
off[n - 1, 0], off[0, n - 1] = -2 * np.pi, 2 * np.pi
ring = pendula.Network(n, topology="ring", strength=kr, offset=off,
                       damping=0.05, bias=0.05)
# the kink at rest without the bias (with it, no rest point: it moves)
still = pendula.Network(n, topology="ring", strength=kr, offset=off)
sites = np.arange(n)
rest = still.equilibrium(4 * np.arctan(np.exp((sites - 10) / math.sqrt(kr))))
tk = np.linspace(0, 300, 601)
chain = ring.simulate(tk, phi0=rest.phi)
# where each element's phase sits near the top (the kink's core)
core = 0.5 * (1 - np.cos(chain.phi.values))

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
ax1.plot(t, own[:, 0], lw=1, label="pendulum 1")
ax1.plot(t, own[:, 1], lw=1, label="pendulum 2")
ax1.axvline(half_beat, color="0.5", ls="--", lw=0.8)
ax1.set(xlabel="t", ylabel="energy", title=f"two pendula, spring K = {k}")
ax1.legend(fontsize=8, loc="upper right")
im = ax2.imshow(core.T, origin="lower", aspect="auto", cmap="magma",
                extent=[tk[0], tk[-1], -0.5, n - 0.5])
ax2.set(xlabel="t", ylabel="element",
        title=f"a kink on a ring of {n}, K = {kr}, bias 0.05")
fig.colorbar(im, ax=ax2, label="(1 − cos φ)/2")
fig.tight_layout()
plt.show()
