"""
A junction in the lab
=====================

A Josephson junction as an experimenter meets it, in amperes, volts and
kelvin: :class:`pendula.Junction` (the RCSJ model on the pendulum, CODATA
2018 constants).  Left: the I-V curve under microwaves, with Shapiro steps at
V = n h f / 2e; a phase-locked bias reports its step voltage exactly.
Right: the switching currents of a ramped bias at two temperatures, with
the Fulton-Dunkleberger distribution of Kramers' escape rate over them.
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula
from pendula.junction import FLUX_QUANTUM

# a 1 uA junction with 1 pF and 18 ohm: plasma frequency 8.8 GHz, beta_c = 0.98
j = pendula.Junction(critical_current=1e-6, resistance=18.0, capacitance=1e-12)
f = 8.0e9  # the microwave frequency, Hz
bias = np.linspace(0.0, 2.5e-6, 126)
dc = j.iv_curve(
    bias, transient=100 / j.plasma_frequency, t_max=300 / j.plasma_frequency
)
rf = j.iv_curve(bias, rf_current=1.0e-6, rf_frequency=f)
print(rf)

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.4))
ax1.plot(
    dc.current * 1e6,
    dc.voltage.sel(direction="up") * 1e6,
    color="0.6",
    lw=1,
    label="no microwaves",
)
v = rf.voltage.sel(direction="up") * 1e6
ax1.plot(
    rf.current * 1e6, v, ".-", ms=3, lw=0.8, label=f"{f / 1e9:g} GHz, 1 µA"
)
locked = rf.status.sel(direction="up") == 6
ax1.plot(
    rf.current[locked] * 1e6,
    v[locked],
    "o",
    mfc="none",
    ms=5,
    color="C3",
    label="phase-locked",
)
for n in range(1, 4):
    ax1.axhline(n * f * FLUX_QUANTUM * 1e6, color="C3", lw=0.5, ls=":")
ax1.set(
    xlabel="bias current (µA)",
    ylabel="dc voltage (µV)",
    title=f"Shapiro steps at n h f / 2e = n × {f * FLUX_QUANTUM * 1e6:.2f} µV",
)
ax1.legend(fontsize=8)

# switching currents: 300 ramps at 1e-4 I_c per 1/omega_p, at two temperatures
ej_kelvin = j.josephson_energy / pendula.junction.BOLTZMANN
rate = 1e-4 * j.critical_current * j.plasma_frequency  # A/s
grid = np.linspace(0.0, 1.0e-6, 600)
for temp, c in ((0.1 * ej_kelvin, "C0"), (0.2 * ej_kelvin, "C1")):
    hot = pendula.Junction(1e-6, 18.0, 1e-12, temperature=temp)
    s = hot.switching_currents(rate, n=300, seed=1, dt=0.1)
    ax2.hist(
        s.samples * 1e6,
        bins=30,
        density=True,
        alpha=0.45,
        color=c,
        label=(f"T = {temp:.2f} K: mean {s.mean * 1e6:.3f} µA, "
               f"width {s.width * 1e9:.0f} nA"),
    )
    ax2.plot(
        grid * 1e6, hot.switching_density(grid, rate) * 1e-6, color=c, lw=1.2
    )
ax2.set(
    xlabel="switching current (µA)",
    ylabel="density (1/µA)",
    title=f"switching currents at dI/dt = {rate:.2g} A/s (lines: theory)",
)
ax2.legend(fontsize=8)
fig.tight_layout()
plt.show()
