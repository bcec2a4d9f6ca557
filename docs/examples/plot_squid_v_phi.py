"""
A dc SQUID: its critical current and its V-Φ curves
===================================================

Two 10 µA junctions (R = 10 Ω, β_c = 0.5) in a loop of 103 pH (β_L = 1).
Left: the static critical current Ic(Φ), the largest bias at which the
SQUID stays at rest, against the two-junction interference law
2I₀ abs(cos πΦ/Φ₀) of a loop without inductance; screening lifts its minimum.
Beside them an asymmetric SQUID (junctions of 8 and 12 µA, α_I = 0.2, the
loop split 35:65, η = 0.3): its lobe shifts and skews, reaching the full
2I₀ at Φ = −β_L(α_I + η)/2 (here 3/4 Φ₀), where the arms' shares of the bias match
the junctions' critical currents.
Right: the dc voltage over the applied flux at four bias currents (the
SQUID as a flux-to-voltage converter), and at 18 µA also at 4.2 K, the
Johnson noise of the shunts rounding the curve (eight noisy paths per flux;
the error bars, their standard error, are smaller than the dots).
"""

import numpy as np
import matplotlib.pyplot as plt

import pendula

i0, r = 10e-6, 10.0
phi0 = pendula.junction.FLUX_QUANTUM
c = 0.5 * phi0 / (2 * np.pi * i0 * r ** 2)       # beta_c = 0.5
inductance = 1.0 * phi0 / (2 * i0)                 # beta_L = 1
sq = pendula.DCSquid(i0, r, c, inductance)
hot = pendula.DCSquid(i0, r, c, inductance, temperature=4.2)
skew = pendula.DCSquid(i0, r, c, inductance, current_asymmetry=0.2, inductance_asymmetry=0.3)

flux = np.linspace(0, 1, 41)
ic = np.array([sq.critical_current(f) for f in flux])
ic_skew = np.array([skew.critical_current(f) for f in flux])

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(7.5, 3.3))
ax1.plot(flux, ic * 1e6, lw=1.5, label="β_L = 1")
ax1.plot(flux, ic_skew * 1e6, lw=1.2, color="tab:purple", label="α_I = 0.2, η = 0.3")
ax1.plot(flux, 2 * i0 * np.abs(np.cos(np.pi * flux)) * 1e6, "--", lw=1, color="0.4", label="β_L → 0")
ax1.set(xlabel="Φ / Φ₀", ylabel="Ic (µA)", title="static critical current")
ax1.legend(fontsize=9, loc="lower left")
for bias in (14e-6, 18e-6, 22e-6, 26e-6):
    curve = sq.v_phi_curve(bias, flux)
    ax2.plot(flux, curve.voltage * 1e6, lw=1.2, label=f"{bias * 1e6:.0f} µA")
noisy = hot.v_phi_curve(18e-6, flux[::2], paths=8, seed=1)
ax2.errorbar(flux[::2], noisy.voltage * 1e6, noisy.voltage_err * 1e6, fmt="o", ms=2.5, color="k",
             label="18 µA, 4.2 K")
ax2.set(xlabel="Φ / Φ₀", ylabel="V (µV)", title="V-Φ at fixed bias")
ax2.set_ylim(-3, 135)
ax2.legend(fontsize=9, loc="upper center", ncol=3, columnspacing=0.8, handlelength=1.2)
fig.tight_layout()
plt.show()
