"""Benchmark: a 201 x 61 Shapiro step map in laboratory units (Junction.sweep) against the same grid
swept by hand in reduced units (pendula.sweep over torque and drive_amplitude), in one run; prints both
times and their ratio, and checks the two maps agree point for point (the same kernel runs both).

The 10 uA / 1 pF / 30 ohm junction at 10 GHz, bias 0-6 uA, rf current 0-12 uA, default windows.

Run: python tools/bench_step_map.py [threads]
"""

import sys
import time

import numpy as np

import pendula


def main():
    threads = int(sys.argv[1]) if len(sys.argv) > 1 else 0
    j = pendula.Junction(10e-6, 30.0, 1e-12)
    bias, rf = np.linspace(0.0, 6e-6, 201), np.linspace(0.0, 12e-6, 61)
    t0 = time.perf_counter()
    lab = j.sweep({"bias": bias, "rf_current": rf}, rf_frequency=10e9, threads=threads)
    t_lab = time.perf_counter() - t0
    scene = pendula.Scene(eps=1.0, damping=j.damping, drive_frequency=j.reduced_frequency(10e9))
    t0 = time.perf_counter()
    red = pendula.sweep(scene, over={"torque": bias / j.critical_current,
                                     "drive_amplitude": rf / j.critical_current},
                        measure="mean_velocity", transient=200.0, t_max=400.0, threads=threads)
    volt = red.mean_velocity.values * float(j.voltage(1.0))
    t_red = time.perf_counter() - t0
    same = (np.array_equal(lab.mean_velocity.values, red.mean_velocity.values, equal_nan=True)
            and np.array_equal(lab.voltage.values, volt, equal_nan=True))
    locked = int((lab.status.values == 6).sum())
    print(f"201 x 61 step map: Junction.sweep {t_lab:.1f} s, reduced-unit pendula.sweep {t_red:.1f} s, "
          f"ratio {t_lab / t_red:.3f}; identical voltages: {same}; locked points {locked} of {lab.status.size}")


if __name__ == "__main__":
    main()
