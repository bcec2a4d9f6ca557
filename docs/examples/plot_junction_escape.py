"""
Switching in the lab, and the overdamped junction
=================================================

A 10 µA, 1 pF, 30 Ω junction as the laboratory measures it.  Top: its
switching-current distributions at 1 A/s and 1 mA/s, at 4.2 K (thermal
activation) and at 20 mK (macroscopic quantum tunnelling), from the
Fulton-Dunkleberger integral of the escape rate
(:func:`pendula.switching_distribution`).  Middle: the width of the
distribution against temperature; below the crossover temperature
(:func:`pendula.crossover_temperature`, marked) tunnelling takes over and the
width stops shrinking.  Bottom: the same junction without its capacitance (the
overdamped RSJ junction): the exact I-V V = R √(I² − I_c²), and under a
100 GHz drive of −56 dBm at 50 Ω its Shapiro steps, exactly n f Φ₀.
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula
from pendula.junction import FLUX_QUANTUM

j = pendula.Junction(critical_current=10e-6, resistance=30.0, capacitance=1e-12)
# one panel a row, so that the figure fits the page's column at full size
fig, (ax1, ax2, ax3) = plt.subplots(3, 1, figsize=(7, 13),
                                    layout="constrained")

for temp, color in ((4.2, "C3"), (0.02, "C0")):
    for rate, ls in ((1.0, "-"), (1e-3, "--")):
        d = pendula.switching_distribution(j, rate, temperature=temp)
        ax1.fill_between(d.currents * 1e6, d.density * 1e-6, color=color,
                         alpha=0.15, step="mid")
        ax1.plot(
            d.currents * 1e6, d.density * 1e-6, ls, color=color,
            label=(f"{temp:g} K, {rate:g} A/s: {d.mean * 1e6:.3f} µA, "
                   f"width {d.width * 1e9:.0f} nA"),
        )
ax1.set(xlabel="switching current (µA)", ylabel="density (1/µA)",
        title="switching at laboratory ramps")
ax1.legend(fontsize=8)

temps = np.geomspace(4e-3, 6.0, 36)
widths = [pendula.switching_distribution(j, 1.0, temperature=t).width
          for t in temps]
cold = pendula.switching_distribution(j, 1.0, temperature=0.0)
t_cr = float(pendula.crossover_temperature(j, cold.mean))
ax2.loglog(temps, np.array(widths) * 1e9, ".-", label="width at 1 A/s")
ax2.axvline(t_cr, color="k", lw=0.8, ls=":")
ax2.text(t_cr * 0.9, 120, f"T_cr = {t_cr * 1e3:.0f} mK\nat the mean I_sw",
         fontsize=8, ha="right")
ax2.set(xlabel="temperature (K)", ylabel="width of P(I) (nA)",
        title="thermal activation above, tunnelling below")
ax2.legend(fontsize=8)

rsj = pendula.Junction(critical_current=10e-6, resistance=30.0,
                       capacitance=0.0)
cur = np.linspace(0.0, 40e-6, 161)
f = 100e9
i_rf = pendula.rf_current(power_dbm=-56.0, impedance=50.0)
dc = rsj.iv_curve(cur)
ac = rsj.iv_curve(cur, rf_current=i_rf, rf_frequency=f,
                  t_max=500 / f)
ax3.plot(cur * 1e6, dc.voltage[0] * 1e6, color="0.5", lw=1,
         label="no rf: R √(I² − I_c²)")
ax3.plot(cur * 1e6, ac.voltage[0] * 1e6, ".-", ms=2.5, lw=0.7,
         label=f"{f / 1e9:g} GHz, −56 dBm at 50 Ω ({i_rf * 1e6:.2f} µA)")
locked = ac.status[0] == 6
ax3.plot(cur[locked] * 1e6, ac.voltage[0][locked] * 1e6, "o", mfc="none",
         ms=4, color="C3", label="phase-locked (exact)")
for n in range(1, 6):
    ax3.axhline(n * f * FLUX_QUANTUM * 1e6, color="C3", lw=0.4, ls=":")
ax3.set(xlabel="bias current (µA)", ylabel="dc voltage (µV)",
        title="the overdamped junction (C = 0)")
ax3.legend(fontsize=8)
plt.show()
