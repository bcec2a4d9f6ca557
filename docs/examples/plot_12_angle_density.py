"""
The density of the angle
========================

Prusa & Tuma, task 5 (gallery scene ``angle_density``): if you look at a
swinging pendulum at a random time, where is it?  The density of θ is
p(θ) = 2/(T·abs(θ')) on (−θmax, θmax): it piles up at the turning points.  For
small amplitudes it tends to the arcsine law 1/(π√(θ0² − θ²)).  The
histogram is θ sampled at random times from a long exact run; the curves are
:func:`pendula.angle_density`.
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula

fig, ax = plt.subplots(figsize=(8, 4.5))
for theta0 in [0.2, 1.0, 2.0, 3.0]:
    sc = pendula.Scene(theta0=theta0)
    th = np.linspace(-theta0, theta0, 801)[1:-1]
    line, = ax.plot(th / theta0, theta0 * pendula.angle_density(sc, th),
                    label=f"θ0 = {theta0:g}")
th = np.linspace(-1, 1, 801)[1:-1]
ax.plot(th, 1 / (np.pi * np.sqrt(1 - th**2)), "k--", lw=1, label="arcsine law")

sc = pendula.Scene(theta0=3.0)
T = pendula.period(sc)
rng = np.random.default_rng(5)
samples = pendula.exact_motion(3.0, 0.0, 1.0,
                               np.sort(rng.uniform(0, 1000 * T, 200_000)))[0]
ax.hist(samples / 3.0, bins=80, density=True, histtype="step", color="0.4",
        label="θ0 = 3, random times")
ax.set(ylim=(0, 3), xlabel="θ / θ0", ylabel="θ0 · p(θ)",
       title="where a pendulum is, at a random time")
ax.legend(fontsize=8)
fig.tight_layout()
plt.show()
