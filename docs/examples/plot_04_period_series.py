"""
The period series and Poincaré–Lindstedt
=========================================

Prusa & Tuma, section 3 (gallery scenes ``period_series`` and
``poincare_lindstedt``).  Left: the period T(θ0)/T0 of a pendulum released
from rest against its series 1 + θ0²/16 + 11θ0⁴/3072 + …, truncated after
1, 2, 4 and 8 terms (pendula computes the coefficients as exact fractions to
any order); the series converges for θ0 < π.  Right: the largest error of
the Poincaré–Lindstedt approximation of θ(t) over ten periods, by order,
against the exact motion (with the sign of the third-order term corrected,
see :doc:`/slips`).
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula

print("T/T0 =",
      " + ".join(f"({c}) θ0^{2 * j}" for j,
                 c in enumerate(pendula.period_series(4))), "+ ...")

theta0 = np.linspace(0.05, 3.0, 120)
T0 = 2 * np.pi
exact = np.array([pendula.orbit(a, 0.0).period for a in theta0]) / T0
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
ax1.plot(theta0, exact, "k", lw=2, label="exact (4K/√ε)")
for n in (1, 2, 4, 8):
    ax1.plot(theta0, pendula.period_from_series(theta0, n) / T0,
             label=f"series to θ0^{2 * n}")
ax1.set(xlabel="θ0", ylabel="T / T0", ylim=(0.95, 2.2),
        title="period against amplitude")
ax1.legend(fontsize=8)

amps = np.logspace(-2, 0, 12)
for order in (1, 3, 5, 7):
    err = []
    for a in amps:
        T = pendula.orbit(a, 0.0).period
        t = np.linspace(0, 10 * T, 2001)
        th_pl = pendula.poincare_lindstedt(a, t, order=order)
        th_ex = pendula.exact_motion(a, 0.0, 1.0, t)[0]
        err.append(np.max(np.abs(th_pl - th_ex)))
    ax2.loglog(amps, err, "o-", ms=3, label=f"order {order}")
ax2.set(xlabel="amplitude a", ylabel="max |θ_PL − θ_exact| over 10 periods",
        title="Poincaré–Lindstedt against the exact motion")
ax2.legend(fontsize=8)
fig.tight_layout()
plt.show()
