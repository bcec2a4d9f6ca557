"""
Huygens' cycloid and non-uniform gravity
========================================

Prusa & Tuma, section 4 and task 4 (gallery scenes ``huygens_cycloid``,
``gravity_inverse_square`` and ``gravity_linear``).  Top: Huygens' clock.
A cord of length 4R wraps on two cycloidal cheeks, so the bob moves on a
cycloid, and its motion is harmonic at every amplitude up to the cusps:
the period 4π√(R/g) does not depend on the amplitude (the tautochrone).
Middle: that period measured from the closed-form motion against the rigid
pendulum's.  Bottom: the period in a non-uniform field (a point mass at
distance D below the pivot, or a linear fall-off), by exact quadrature.
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula

g = pendula.cycloid_geometry(0.25)
# one panel a row, so that the figure fits the page's column at full size
fig, (ax1, ax2, ax3) = plt.subplots(3, 1, figsize=(7, 12.5),
                                    layout="constrained")
ax1.plot(*g.cheek_left, "k", lw=2.5)
ax1.plot(*g.cheek_right, "k", lw=2.5, label="cheeks (cycloids)")
ax1.plot(*g.path, color="tab:blue", label="bob's path (cycloid)")
ax1.plot(*g.circle, "--", color="tab:red", lw=0.8,
         label="rigid pendulum's circle")
for th in np.linspace(-1.2, 1.2, 7):
    wrapped, contact, bob = g.cord(th)
    ax1.plot(*wrapped, color="tab:orange", lw=1.5)
    ax1.plot([contact[0], bob[0]], [contact[1], bob[1]], color="tab:orange",
             lw=1)
    ax1.plot(*bob, "o", color="tab:green", ms=5)
ax1.set(aspect="equal", title="Huygens' clock, R = l/4", xlabel="x / l",
        ylabel="y / l", ylim=(-0.05, 1.25))
ax1.legend(fontsize=8, loc="upper center", ncols=3)

amps = np.linspace(0.05, 1.5, 30)
Tc = [pendula.period(pendula.Scene(guide="cycloid", theta0=a)) for a in amps]
Tr = [pendula.period(pendula.Scene(theta0=a)) for a in amps]
ax2.plot(amps, Tc, label="cycloid: 4π√(R/g)")
ax2.plot(amps, Tr, label="rigid pendulum")
ax2.set(xlabel="θ0", ylabel="period (ε = 1)", title="isochronism")
ax2.legend(fontsize=8)

amps = np.linspace(0.05, 3.0, 40)
fields = [("uniform", {}),
          ("inverse-square, D = 1.5 l",
           {"gravity": "inverse-square", "gravity_distance": 1.5}),
          ("inverse-square, D = 3 l",
           {"gravity": "inverse-square", "gravity_distance": 3.0}),
          ("linear, κ = 0.45",
           {"gravity": "linear", "gravity_gradient": 0.45}),
          ("linear, κ = −0.5",
           {"gravity": "linear", "gravity_gradient": -0.5})]
for label, kw in fields:
    ax3.semilogy(amps,
                 [pendula.period(pendula.Scene(theta0=a, **kw)) for a in amps],
                 label=label)
ax3.set(xlabel="θ0", ylabel="period",
        title="non-uniform gravity (exact quadrature)")
ax3.legend(fontsize=8)
plt.show()
