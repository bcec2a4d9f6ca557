"""
Periodic orbits on the bifurcation diagram
==========================================

The driven damped pendulum θ'' + β θ' + sin θ = A cos(Ωt), β = 0.5, Ω = 2/3.
Grey: the stroboscopic points after a transient (:func:`pendula.sweep`,
measure ``poincare``).  Coloured: the period-1 oscillation found by Newton
on the monodromy (:func:`pendula.periodic_orbit`), followed in A by using
each orbit as the next guess; solid where its Floquet multipliers lie
inside the unit circle, open where one has crossed −1 (the period
doubling), and the period-2 orbit born there.  Below: the largest Floquet
exponent log|μ|/T of the orbits against the Lyapunov exponent of the
attractor (measure ``lyapunov``).
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula

drive = pendula.Scene(damping=0.5, drive_frequency=2 / 3, rtol=1e-9,
                      atol=1e-11)
amps = np.linspace(0.9, 1.12, 45)
bif = pendula.sweep(drive, over={"drive_amplitude": amps}, measure="poincare",
                    transient=600.0, samples=16)
lya = pendula.sweep(drive, over={"drive_amplitude": amps}, measure="lyapunov",
                    transient=300.0, t_max=900.0)

p1, p2 = [], []
guess = (0.5, 0.5)
for a in amps:
    po = pendula.periodic_orbit(drive.replace(drive_amplitude=float(a)),
                                guess=guess)
    guess = (po.theta, po.v)
    p1.append((a, po.v, po.stable, po.exponents[0]))
guess2 = None
for a in amps[amps > 1.066]:
    sc = drive.replace(drive_amplitude=float(a))
    if guess2 is None:
        i = int(np.argmin(abs(amps - a)))
        guess2 = (float(bif.theta.values[i, 0]), float(bif.v.values[i, 0]))
    try:
        po = pendula.periodic_orbit(sc, guess=guess2, k=2)
    except ValueError:
        continue
    guess2 = (po.theta, po.v)
    end = pendula.simulate(sc.replace(theta0=po.theta, v0=po.v),
                           [0.0, po.period / 2])
    p2.append((a, po.v, end.v[-1], po.stable, po.exponents[0]))

fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
ax1.plot(np.repeat(amps, bif.sizes["sample"]), bif.v.values.ravel(), ".",
         ms=2, color="0.6")
for a, v, stable, _ in p1:
    ax1.plot(a, v, "o", ms=4, color="tab:blue",
             mfc="tab:blue" if stable else "none")
for a, v, v2, stable, _ in p2:
    ax1.plot([a, a], [v, v2], "s", ms=3, color="tab:orange",
             mfc="tab:orange" if stable else "none")
ax1.set(ylabel="v on the section",
        title="period-1 (blue) and period-2 (orange) orbits by Newton")
ax2.plot(lya.drive_amplitude, lya.lyapunov, "k.-", ms=3,
         label="Lyapunov exponent of the attractor")
ax2.plot([p[0] for p in p1], [p[3] for p in p1], "o", ms=3, mfc="none",
         color="tab:blue",
         label="period-1 orbit: log|μ|/T")
ax2.plot([p[0] for p in p2], [p[4] for p in p2], "s", ms=3, mfc="none",
         color="tab:orange",
         label="period-2 orbit: log|μ|/T")
ax2.axhline(0, color="0.6", lw=0.8)
ax2.set(xlabel="drive amplitude A", ylabel="exponent")
ax2.legend(fontsize=8)
fig.tight_layout()
plt.show()
