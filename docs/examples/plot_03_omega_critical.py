"""
Frequency, amplitude and the critical slowing at v0 = 2
========================================================

Suzuki & Suzuki, Figs. 8–13 (gallery scenes ``fig10_theta_max_vs_v0``,
``fig13_omega_vs_v0`` and ``fig9_12_critical_omega``).  Left: the angular
frequency ω = 2π/T and the amplitude θmax against v0 (θ0 = 0, ε = 1); ω
falls to 0 at the separatrix v0 = 2 from both sides.  Right: how it falls.
With t the distance of v0 from 2, the frequency approaches (π/2)/ln(4/√t) from below and
π/ln(4/√t) from above (a ratio of 2: a rotation's period is one turn, a
libration's two passes).  The orbits are exact, so t reaches 10⁻¹².
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula

v0 = np.concatenate([np.linspace(0.01, 1.99, 199), np.linspace(2.01, 4, 200)])
orbits = [pendula.orbit(0.0, v) for v in v0]
omega = np.array([o.omega for o in orbits])
theta_max = np.array([o.theta_max for o in orbits])

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
ax1.plot(v0, omega, label="ω = 2π/T")
ax1.plot(v0, np.where(np.isfinite(theta_max), theta_max, np.nan), label="θmax")
ax1.axvline(2, color="0.7", lw=0.8)
ax1.set(xlabel="v0", title="ω and θmax against v0 (ε = 1)")
ax1.legend()

t = np.logspace(-12, -1, 45)
for side, sign, c, asym in (("below", -1, "tab:blue", np.pi / 2),
                            ("above", 1, "tab:green", np.pi)):
    w = np.array([pendula.orbit(0.0, 2 + sign * x).omega for x in t])
    ax2.semilogx(t, w, "o", ms=3, color=c,
                 label=f"v0 = 2 {'−' if sign < 0 else '+'} t (exact)")
    ax2.semilogx(t, asym / np.log(4 / np.sqrt(t)), color=c, lw=0.8,
                 label=f"{'(π/2)' if sign < 0 else 'π'} / ln(4/√t)")
ax2.set(xlabel="t = abs(v0 − 2)", ylabel="ω",
        title="critical behaviour at the separatrix")
ax2.legend(fontsize=8)
fig.tight_layout()
plt.show()
