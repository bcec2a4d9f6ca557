"""
Shapiro steps in the lab: the I-V curve in µV and the step map
==============================================================

The 10 µA, 1 pF, 30 Ω junction (β_c = 27, hysteretic) under 10 GHz
microwaves, in the laboratory's units.  Left: its I-V curve up and down the
bias ramp with 6 µA of rf (:meth:`pendula.Junction.iv_curve`, drawn by
:func:`pendula.plot.iv`): the n = 4 step at 4 × 20.68 µV holds from 3.75 to
4.80 µA on this grid of 0.05 µA, every bias on it phase-locked and exact, with chaos below it.
Right: the step map over dc bias and rf current
(:meth:`pendula.Junction.sweep`, drawn by :func:`pendula.plot.steps`): the
step each point locks to from rest, white where it does not lock; the ticks
mark the plateaus' edges.  :meth:`pendula.Junction.steps` gives each
plateau's voltage, edges and width as numbers.
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula
import pendula.plot

j = pendula.Junction(critical_current=10e-6, resistance=30.0, capacitance=1e-12)
f = 10e9
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(8, 3.6), layout="constrained")

bias = np.round(np.arange(0.0, 6.0001, 0.05), 10) * 1e-6
iv = j.iv_curve(bias, rf_current=6e-6, rf_frequency=f, direction="both")
pendula.plot.iv(iv, ax=ax1)
ax1.set_title("I-V at 10 GHz, 6 µA rf")

steps = j.steps(bias, 6e-6, f)
for p in steps.plateau.values:  # each plateau: step, voltage (µV), edges and width (µA)
    s = steps.sel(plateau=p)
    print(f"n = {float(s.order):g}: {float(s.voltage) * 1e6:7.2f} µV, "
          f"{float(s.lower) * 1e6:.2f}-{float(s.upper) * 1e6:.2f} µA, "
          f"width {float(s.width) * 1e6:.2f} µA")

m = j.sweep(
    {"bias": np.linspace(0.0, 6e-6, 41), "rf_current": np.linspace(0.0, 12e-6, 25)},
    rf_frequency=f,
)
pendula.plot.steps(m, ax=ax2)
ax2.set_title("step map (from rest)")
plt.show()
