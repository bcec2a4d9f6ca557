"""Shapiro step widths of the overdamped-limit junction against the Bessel law.

The RCSJ junction theta'' + beta theta' + sin(theta) = i + a cos(Omega t) at
large damping (beta = 10: Stewart-McCumber beta_c = 0.01) is the RSJ model
with time in units of beta; at a high rf frequency (Omega_c = Omega beta = 10
characteristic frequencies) the n-th step spans a bias range of width
2 |J_n(a / Omega_c)| (Barone and Paterno, "Physics and Applications of the
Josephson Effect", section 11.2; exact for a voltage-biased junction, the
high-frequency limit of a current-biased one).  This script measures the
widths with pendula.sweep (measure mean_velocity: a point is on step n when
it is phase-locked with step number n) on a bias grid, for the steps n = 0,
1, 2 and drive amplitudes x = a / Omega_c in [0, 4], and stores them with
the Bessel law (scipy.special.jv) in data/junction/shapiro_steps.json, and
the figure docs/figures/josephson_shapiro.png.

Run: python data/gen_shapiro_steps.py   (a few minutes on two cores)
"""

import json
import pathlib
import platform
import sys
import time

import numpy as np
from scipy.special import jv

import pendula

HERE = pathlib.Path(__file__).resolve().parent
BETA = 10.0
ROOT = HERE.parent


def widths(omega_c, xs, n_bias=261):
    omega = omega_c / BETA
    bias = np.linspace(0.0, 2.6 * omega_c, n_bias)
    db = bias[1] - bias[0]
    out = {n: [] for n in (0, 1, 2)}
    period = 2 * np.pi / omega
    for x in xs:
        a = x * omega_c
        s = pendula.Scene(damping=BETA, drive_amplitude=max(a, 1e-300), drive_frequency=omega, rtol=1e-9,
                          atol=1e-11)
        ds = pendula.sweep(s, over={"torque": bias}, measure="mean_velocity", transient=200 * period,
                           t_max=40 * period)
        # on step n: phase-locked with step number n, or (converging too slowly near a step's edge to be
        # detected in 240 periods) a mean velocity within 1e-3 Omega of n Omega
        near = np.round(ds.mean_velocity.values / omega)
        step = np.where(ds.status.values == 6, ds.step.values,
                        np.where(np.abs(ds.mean_velocity.values / omega - near) < 1e-3, near, np.nan))
        for n in (0, 1, 2):
            # the step is a range of biases on both sides of 0 for n = 0: count i >= 0 twice (symmetric)
            k = np.count_nonzero(step == n)
            out[n].append(float((2 * k - 1) * db if n == 0 and k else k * db))
    return bias, out


def main():
    t0 = time.time()
    xs = np.linspace(0.0, 4.0, 11)
    rec = {"what": "Shapiro step widths (in units of I_c) of theta'' + beta theta' + sin(theta) = i + "
                   "a cos(Omega t), beta = 10, against 2 |J_n(a / (Omega beta))|",
           "beta": BETA, "x": xs.tolist(), "runs": {}}
    for omega_c in (10.0,):
        bias, w = widths(omega_c, xs)
        rec["runs"][str(omega_c)] = {"omega_c": omega_c, "bias_resolution": float(bias[1] - bias[0]),
                                     "measured": {str(n): w[n] for n in w},
                                     "bessel": {str(n): [float(2 * abs(jv(n, x))) for x in xs] for n in w}}
    rec["date"] = time.strftime("%Y-%m-%d")
    rec["machine"] = {"python": sys.version.split()[0], "platform": platform.platform()}
    rec["seconds"] = time.time() - t0
    (HERE / "junction").mkdir(exist_ok=True)
    (HERE / "junction" / "shapiro_steps.json").write_text(json.dumps(rec, indent=1))
    plot(rec)


def plot(rec):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    x = np.array(rec["x"])
    fine = np.linspace(0, x.max(), 400)
    fig, ax = plt.subplots(figsize=(6, 3.8))
    for key, run in rec["runs"].items():
        for n, c in zip(("0", "1", "2"), ("C0", "C1", "C2")):
            ax.plot(fine, 2 * np.abs(jv(int(n), fine)), color=c, lw=1)
            ax.plot(x, run["measured"][n], "o", ms=3.5, color=c, label=f"n = {n}")
        ax.set(xlabel="rf amplitude a / Ω_c", title=f"β = {rec['beta']:g}, Ω_c = Ωβ = {run['omega_c']:g}")
        ax.legend(fontsize=8)
    ax.set_ylabel("step width / I_c")
    fig.suptitle("Shapiro step widths (dots: pendula) and the Bessel law 2|J_n| (lines)", fontsize=10)
    fig.tight_layout()
    fig.savefig(ROOT / "docs" / "figures" / "josephson_shapiro.png", dpi=110)


if __name__ == "__main__":
    main()
